// FieldTable: a config section's schema as data. Each entry names a YAML key, the member of the
// parameter struct it sets and whether it is required; the loader reads through the table, the
// writers (vmass-calibrate, the simulator) write through it, and the formats-doc test checks
// docs/formats.md against it, so that a key exists in one place.
//
//   inline constexpr std::array<Field<RlsParams>, 2> kRlsFields{{
//       {"noise_std_n", &RlsParams::noise_std_n},
//       {"forgetting_factor", &RlsParams::forgetting_factor},
//   }};
//   read_fields(reader, kRlsFields, &params);      // errors name the file, line and key
//   emit_fields(emitter, kRlsFields, params, {});  // "noise_std_n: 100" ...
//
// Configuration time only; not thread-safe (YAML::Emitter).
#pragma once

#include <array>
#include <cstddef>
#include <initializer_list>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "vmass/config/yaml_reader.hpp"
#include "vmass/core/longitudinal_extractor.hpp"
#include "vmass/core/pipeline.hpp"

namespace vmass {

/// The value types a config key can have.
template <class S>
using FieldMember = std::variant<double S::*, int S::*, long S::*, bool S::*, std::string S::*,
                                 std::vector<double> S::*, std::vector<int> S::*,
                                 RegressorType S::*, AccelSource S::*, RotatingAccelSource S::*>;

template <class S>
struct Field {
  const char* key;
  FieldMember<S> member;
  bool required = false;
};

/// A comment per key, for the writers ("" or absent: none).
using FieldComments = std::map<std::string, std::string>;

/// Which keys a writer writes: all of them, or the required ones and those whose value differs
/// from the struct's default (a generated config then says only what is known about the car).
enum class FieldSelection { kAll, kRequiredOrSet };

/// The names an enum-valued key accepts.
template <class E>
struct EnumNames;
template <>
struct EnumNames<RegressorType> {
  static constexpr std::array<RegressorType, 2> kAll{RegressorType::kRls, RegressorType::kBayes};
  static std::string_view name(RegressorType t) { return regressor_type_name(t); }
};
template <>
struct EnumNames<AccelSource> {
  static constexpr std::array<AccelSource, 3> kAll{
      AccelSource::kAccelerometer, AccelSource::kWheelSpeed, AccelSource::kCalibrated};
  static std::string_view name(AccelSource s) { return accel_source_name(s); }
};

template <>
struct EnumNames<RotatingAccelSource> {
  static constexpr std::array<RotatingAccelSource, 3> kAll{RotatingAccelSource::kAuto,
                                                           RotatingAccelSource::kWheelSpeed,
                                                           RotatingAccelSource::kAccelerometer};
  static std::string_view name(RotatingAccelSource s) { return rotating_accel_source_name(s); }
};

namespace field_detail {

/// "'a' or 'b'", "'a', 'b' or 'c'"
template <class E>
std::string choices_text() {
  std::string out;
  const auto& all = EnumNames<E>::kAll;
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (i > 0) out += i + 1 == all.size() ? " or " : ", ";
    out += "'" + std::string(EnumNames<E>::name(all[i])) + "'";
  }
  return out;
}

template <class T>
void read_value(YamlReader& r, const char* key, T* out) {
  r.read(key, out);
}

template <class E>
void read_enum(YamlReader& r, const char* key, E* out) {
  std::string text(EnumNames<E>::name(*out));
  r.read(key, &text);
  for (E value : EnumNames<E>::kAll) {
    if (EnumNames<E>::name(value) == text) {
      *out = value;
      return;
    }
  }
  r.fail(key, "expected " + choices_text<E>() + ", got '" + text + "'");
}
inline void read_value(YamlReader& r, const char* key, RegressorType* out) {
  read_enum(r, key, out);
}
inline void read_value(YamlReader& r, const char* key, AccelSource* out) { read_enum(r, key, out); }
inline void read_value(YamlReader& r, const char* key, RotatingAccelSource* out) {
  read_enum(r, key, out);
}

template <class T>
void emit_value(YAML::Emitter& out, const T& value) {
  out << value;
}
template <class T>
void emit_value(YAML::Emitter& out, const std::vector<T>& values) {
  out << YAML::Flow << YAML::BeginSeq;
  for (const T& v : values) out << v;
  out << YAML::EndSeq;
}
inline void emit_value(YAML::Emitter& out, RegressorType t) {
  out << std::string(EnumNames<RegressorType>::name(t));
}
inline void emit_value(YAML::Emitter& out, AccelSource s) {
  out << std::string(EnumNames<AccelSource>::name(s));
}
inline void emit_value(YAML::Emitter& out, RotatingAccelSource s) {
  out << std::string(EnumNames<RotatingAccelSource>::name(s));
}

}  // namespace field_detail

/// Reads the field into *params when present; a required field must be. Throws ConfigError.
template <class S>
void read_field(YamlReader& r, const Field<S>& field, S* params) {
  if (field.required && !r.has(field.key)) r.fail(field.key, "required key is missing");
  std::visit([&](auto member) { field_detail::read_value(r, field.key, &(params->*member)); },
             field.member);
}

template <class S, std::size_t N>
void read_fields(YamlReader& r, const std::array<Field<S>, N>& table, S* params) {
  for (const Field<S>& field : table) read_field(r, field, params);
}

template <class S>
bool field_equal(const Field<S>& field, const S& a, const S& b) {
  return std::visit([&](auto member) { return a.*member == b.*member; }, field.member);
}

/// `key: value` (and its comment) into an emitter that is inside a map.
template <class S>
void emit_field(YAML::Emitter& out, const Field<S>& field, const S& params,
                const std::string& comment = "") {
  out << YAML::Key << field.key << YAML::Value;
  std::visit([&](auto member) { field_detail::emit_value(out, params.*member); }, field.member);
  if (!comment.empty()) out << YAML::Comment(comment);
}

template <class S, std::size_t N>
void emit_fields(YAML::Emitter& out, const std::array<Field<S>, N>& table, const S& params,
                 const FieldComments& comments, FieldSelection which = FieldSelection::kAll) {
  static const S defaults{};  // (built once: a default-constructed struct is constant)
  for (const Field<S>& field : table) {
    const bool skip = which == FieldSelection::kRequiredOrSet && !field.required &&
                      field_equal(field, params, defaults);
    if (skip) continue;
    const auto comment = comments.find(field.key);
    emit_field(out, field, params, comment == comments.end() ? "" : comment->second);
  }
}

/// Only the named keys, in the given order: what a writer knows. A name the table lacks is a
/// programming error (std::logic_error).
template <class S, std::size_t N>
void emit_fields(YAML::Emitter& out, const std::array<Field<S>, N>& table, const S& params,
                 const FieldComments& comments, std::initializer_list<std::string_view> keys);

/// The table's entry for `key`; nullptr when it has none.
template <class S, std::size_t N>
const Field<S>* find_field(const std::array<Field<S>, N>& table, std::string_view key) {
  for (const Field<S>& field : table) {
    if (key == field.key) return &field;
  }
  return nullptr;
}

template <class S, std::size_t N>
void emit_fields(YAML::Emitter& out, const std::array<Field<S>, N>& table, const S& params,
                 const FieldComments& comments, std::initializer_list<std::string_view> keys) {
  for (std::string_view key : keys) {
    const Field<S>* field = find_field(table, key);
    if (field == nullptr) throw std::logic_error("no config key '" + std::string(key) + "'");
    const auto comment = comments.find(field->key);
    emit_field(out, *field, params, comment == comments.end() ? "" : comment->second);
  }
}

}  // namespace vmass
