#include "vmass/config/suspension_section.hpp"

namespace vmass {

void emit_suspension_section(YAML::Emitter& out, const SuspensionParams& params,
                             const SuspensionComments& comments) {
  out << YAML::Key << "suspension" << YAML::Value << YAML::BeginMap;
  for (std::size_t i = 0; i < kSuspensionFields.size(); ++i) {
    const SuspensionField& field = kSuspensionFields[i];
    out << YAML::Key << field.key << YAML::Value << params.*field.member;
    if (!comments[i].empty()) out << YAML::Comment(comments[i]);
  }
  out << YAML::EndMap;
}

std::string suspension_section_yaml(const SuspensionParams& params,
                                    const SuspensionComments& comments, int precision) {
  YAML::Emitter out;
  out.SetDoublePrecision(precision);
  out << YAML::BeginMap;
  emit_suspension_section(out, params, comments);
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace vmass
