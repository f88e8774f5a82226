#include "vmass/config/suspension_section.hpp"

namespace vmass {

void read_suspension_section(YamlReader r, bool present, SuspensionParams* params) {
  params->has_sensor = present;
  if (!present) return;
  r.read("levelled", &params->levelled);
  for (Field<SuspensionParams> field : kSuspensionFields) {
    field.required = field.required && !params->levelled;
    read_field(r, field, params);
  }
  r.reject_unknown_keys();
}

void emit_suspension_section(YAML::Emitter& out, const SuspensionParams& params,
                             const FieldComments& comments, FieldSelection which) {
  out << YAML::Key << "suspension" << YAML::Value << YAML::BeginMap;
  emit_fields(out, kSuspensionFields, params, comments, which);
  out << YAML::EndMap;
}

std::string suspension_section_yaml(const SuspensionParams& params, const FieldComments& comments,
                                    int precision) {
  YAML::Emitter out;
  out.SetDoublePrecision(precision);
  out << YAML::BeginMap;
  emit_suspension_section(out, params, comments);
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace vmass
