// The `suspension:` section of the config (eq. 3; docs/formats.md): one field table that the
// loader reads and every writer writes (vmass-calibrate's snippet, the simulator's config.yaml
// and its static-ballast truth), so that the schema exists in one place.
//
//   suspension:
//     stiffness_n_per_m: ...          (required)
//     empty_deflection_m: ...
//     progressive_knee_m: ...
//     progressive_rate_n_per_m2: ...
//     linear_range_kg: ...
//     calibrated_range_kg: ...
//
// Configuration time only; not thread-safe (YAML::Emitter).
#pragma once

#include <array>
#include <cstddef>
#include <string>

#include <yaml-cpp/yaml.h>

#include "vmass/core/static_initializer.hpp"

namespace vmass {

struct SuspensionField {
  const char* key;
  double SuspensionParams::*member;
  bool required;
};

inline constexpr std::array<SuspensionField, 6> kSuspensionFields{{
    {"stiffness_n_per_m", &SuspensionParams::stiffness_n_per_m, true},
    {"empty_deflection_m", &SuspensionParams::empty_deflection_m, false},
    {"progressive_knee_m", &SuspensionParams::progressive_knee_m, false},
    {"progressive_rate_n_per_m2", &SuspensionParams::progressive_rate_n_per_m2, false},
    {"linear_range_kg", &SuspensionParams::linear_range_kg, false},
    {"calibrated_range_kg", &SuspensionParams::calibrated_range_kg, false},
}};

/// A comment per field (kSuspensionFields' order); "" for none.
using SuspensionComments = std::array<std::string, kSuspensionFields.size()>;

/// Emits `suspension` and its map (the keys above, in that order, with the comments) into an
/// emitter that is inside a map; the emitter's double precision applies.
void emit_suspension_section(YAML::Emitter& out, const SuspensionParams& params,
                             const SuspensionComments& comments = {});

/// The section as YAML text ("suspension:\n  stiffness_n_per_m: ...\n"), numbers with
/// `precision` significant digits (infinities as .inf).
std::string suspension_section_yaml(const SuspensionParams& params,
                                    const SuspensionComments& comments = {}, int precision = 10);

}  // namespace vmass
