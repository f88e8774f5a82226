#include "vmass/config/estimator_section.hpp"

#include <vector>

namespace vmass {
namespace {

/// Reads each level through its reader; a level's unknown keys are refused when it ends.
class SectionReader {
 public:
  explicit SectionReader(YamlReader top) { levels_.push_back(std::move(top)); }

  template <class S, std::size_t N>
  void fields(const std::array<Field<S>, N>& table, S& params) {
    read_fields(levels_.back(), table, &params);
  }
  void begin(const char* key) {
    YamlReader nested = levels_.back().child(key);
    levels_.push_back(std::move(nested));
  }
  void end() {
    levels_.back().reject_unknown_keys();
    levels_.pop_back();
  }

 private:
  std::vector<YamlReader> levels_;
};

class SectionEmitter {
 public:
  explicit SectionEmitter(YAML::Emitter& out) : out_(out) {}

  template <class S, std::size_t N>
  void fields(const std::array<Field<S>, N>& table, const S& params) {
    emit_fields(out_, table, params, {});
  }
  void begin(const char* key) { out_ << YAML::Key << key << YAML::Value << YAML::BeginMap; }
  void end() { out_ << YAML::EndMap; }

 private:
  YAML::Emitter& out_;
};

}  // namespace

void read_estimator_section(YamlReader r, EstimatorParams* params) {
  SectionReader reader(std::move(r));
  walk_estimator_section(reader, *params);
  reader.end();
}

void emit_estimator_section(YAML::Emitter& out, const EstimatorParams& params) {
  SectionEmitter emitter(out);
  emitter.begin("estimator");
  walk_estimator_section(emitter, params);
  emitter.end();
}

}  // namespace vmass
