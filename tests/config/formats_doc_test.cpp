// docs/formats.md against the loaders: the configuration block it shows is a config the loaders
// accept as it stands (every key it documents exists), and every key the loaders read is in it
// (no key goes undocumented). The loaders' keys are the string literals they pass to
// YamlReader::read / require / child / raw / has.
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include <map>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "vmass/config/config.hpp"
#include "vmass/config/estimator_section.hpp"
#include "vmass/config/suspension_section.hpp"
#include "vmass/config/vehicle_section.hpp"
#include "vmass/service/service_config.hpp"

namespace vmass {
namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The first ```yaml block of docs/formats.md.
std::string documented_config() {
  const std::string doc = read_file(VMASS_SOURCE_DIR "/docs/formats.md");
  const std::string open = "```yaml\n";
  const std::size_t begin = doc.find(open);
  const std::size_t end = doc.find("```", begin + open.size());
  if (begin == std::string::npos || end == std::string::npos) return "";
  return doc.substr(begin + open.size(), end - begin - open.size());
}

/// The keys the given loader sources read: calls with a literal key, and the entries of field
/// tables ({"key", &Struct::member, ...}).
std::set<std::string> loader_keys(std::initializer_list<const char*> files) {
  std::set<std::string> keys;
  const std::regex call(
      R"re(\b(?:read|require|child|raw|has|begin)\("([a-z_0-9]+)"|\{"([a-z_0-9]+)",\s*&[A-Za-z]+::)re");
  for (const char* file : files) {
    const std::string source = read_file(std::string(VMASS_SOURCE_DIR) + file);
    EXPECT_FALSE(source.empty()) << file;
    for (std::sregex_iterator it(source.begin(), source.end(), call), end; it != end; ++it) {
      keys.insert((*it)[1].matched ? (*it)[1].str() : (*it)[2].str());
    }
  }
  return keys;
}

TEST(FormatsDoc, TheDocumentedConfigLoadsAsItStands) {
  const std::string text = documented_config();
  ASSERT_FALSE(text.empty()) << "no ```yaml block in docs/formats.md";
  const ConfigLoad loaded = load_config_text(text, "docs/formats.md");
  ASSERT_TRUE(loaded.ok()) << loaded.error;
  const service::ServiceSettingsLoad settings = service::load_service_settings(*loaded.config);
  EXPECT_TRUE(settings.ok()) << settings.error;
}

/// Keys of the loaders whose sections docs/formats.md documents (the can.inputs entries are
/// documented in docs/signal-mapping.md).
std::set<std::string> loader_keys() {
  return loader_keys(
      {"/src/config/config.cpp", "/include/vmass/config/vehicle_section.hpp",
       "/include/vmass/config/suspension_section.hpp", "/src/config/suspension_section.cpp",
       "/include/vmass/config/estimator_section.hpp", "/include/vmass/service/service_config.hpp",
       "/src/service/service_config.cpp"});
}

TEST(FormatsDoc, EveryKeyTheLoadersReadIsDocumented) {
  const std::string text = documented_config();
  const std::set<std::string> keys = loader_keys();
  ASSERT_GT(keys.size(), 80u) << "the loaders' keys were not found in their sources";
  for (const std::string& key : keys) {
    const std::regex documented("(^|\n) *" + key + ":");
    EXPECT_TRUE(std::regex_search(text, documented))
        << key << " is read by the loader but not documented in docs/formats.md";
  }
}

/// Every key that has a default, by its full path, with its value as the writers write it.
class DefaultedValues {
 public:
  template <class S, std::size_t N>
  void fields(const std::array<Field<S>, N>& table, const S& params) {
    for (const Field<S>& field : table) {
      if (field.required) continue;  // no default: the documented value is an example
      YAML::Emitter out;
      out.SetDoublePrecision(17);
      out << YAML::BeginMap;
      emit_field(out, field, params);
      out << YAML::EndMap;
      values[prefix() + field.key] = out.c_str();
    }
  }
  void begin(const char* key) { path_.emplace_back(key); }
  void end() { path_.pop_back(); }

  std::map<std::string, std::string> values;

 private:
  std::string prefix() const {
    std::string out;
    for (const std::string& p : path_) out += p + ".";
    return out;
  }
  std::vector<std::string> path_;
};

std::map<std::string, std::string> defaulted_values(const PipelineParams& pipeline,
                                                    const service::ServiceSettings& service) {
  DefaultedValues v;
  v.begin("vehicle");
  v.fields(kVehicleFields, pipeline.vehicle);
  v.end();
  v.begin("suspension");
  v.fields(kSuspensionFields, pipeline.suspension);
  v.end();
  v.begin("estimator");
  walk_estimator_section(v, pipeline.estimator);
  v.end();
  v.begin("lcm");
  v.fields(service::kLcmFields, service.lcm);
  v.end();
  v.begin("daemon");
  v.fields(service::kDaemonFields, service.daemon);
  v.begin("realtime");
  v.fields(service::kRealtimeFields, service.daemon.realtime);
  v.end();
  v.end();
  return v.values;
}

/// Whether "a.b.c" is a key of the YAML map tree.
bool has_path(const YAML::Node& root, const std::string& path) {
  YAML::Node node = YAML::Clone(root);
  std::size_t begin = 0;
  while (true) {
    const std::size_t dot = path.find('.', begin);
    const std::string key = path.substr(begin, dot == std::string::npos ? dot : dot - begin);
    if (!node.IsMap() || !node[key]) return false;
    if (dot == std::string::npos) return true;
    node.reset(node[key]);
    begin = dot + 1;
  }
}

// The block shows every key of every table at its default (the required ones excepted), so
// that a reader who copies it changes nothing by accident, and docs/formats.md cannot say one
// default while the loader takes another.
TEST(FormatsDoc, TheDocumentedValuesAreTheTablesDefaults) {
  const ConfigLoad loaded = load_config_text(documented_config(), "docs/formats.md");
  ASSERT_TRUE(loaded.ok()) << loaded.error;
  const service::ServiceSettingsLoad settings = service::load_service_settings(*loaded.config);
  ASSERT_TRUE(settings.ok()) << settings.error;
  const auto documented = defaulted_values(loaded.config->pipeline, settings.settings);
  const auto defaults = defaulted_values(PipelineParams{}, service::ServiceSettings{});
  ASSERT_GT(defaults.size(), 100u);
  const YAML::Node doc = YAML::Load(documented_config());
  for (const auto& [path, value] : defaults) {
    EXPECT_TRUE(has_path(doc, path)) << path << " is not in docs/formats.md";
    EXPECT_EQ(documented.at(path), value) << path << ": docs/formats.md shows another value";
  }
}

}  // namespace
}  // namespace vmass

namespace vmass {
namespace {

// docs/signal-mapping.md documents the can: section: every key its loaders read (can.inputs,
// can.e2e, can.plausibility) appears there as "key:".
TEST(FormatsDoc, EveryCanKeyIsInTheSignalMappingDoc) {
  const std::string doc = read_file(VMASS_SOURCE_DIR "/docs/signal-mapping.md");
  const std::set<std::string> keys =
      loader_keys({"/src/signals/signal_mapping.cpp", "/src/signals/message_protection.cpp",
                   "/src/signals/plausibility_params.cpp"});
  ASSERT_GT(keys.size(), 30u) << "the can: loaders' keys were not found in their sources";
  for (const std::string& key : keys) {
    const std::regex documented("[ {,]" + key + ":");
    EXPECT_TRUE(std::regex_search(doc, documented))
        << key << " is read by the can: loaders but not documented in docs/signal-mapping.md";
  }
}

}  // namespace
}  // namespace vmass
