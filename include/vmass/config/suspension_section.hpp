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
#include <string>

#include <yaml-cpp/yaml.h>

#include "vmass/config/field_table.hpp"
#include "vmass/core/static_initializer.hpp"

namespace vmass {

// `levelled: true` (a self-levelling axle) is read beside the table: it makes no key required.
inline constexpr std::array<Field<SuspensionParams>, 6> kSuspensionFields{{
    {"stiffness_n_per_m", &SuspensionParams::stiffness_n_per_m, true},
    {"empty_deflection_m", &SuspensionParams::empty_deflection_m, false},
    {"progressive_knee_m", &SuspensionParams::progressive_knee_m, false},
    {"progressive_rate_n_per_m2", &SuspensionParams::progressive_rate_n_per_m2, false},
    {"linear_range_kg", &SuspensionParams::linear_range_kg, false},
    {"calibrated_range_kg", &SuspensionParams::calibrated_range_kg, false},
}};

/// Reads the section. Not present: the car has no rear deflection sensor (the estimator starts
/// from the no-static prior). `levelled: true`: it has one on a self-levelling axle, which reads
/// no load, and no key is required. Unknown keys are errors. Throws ConfigError.
void read_suspension_section(YamlReader r, bool present, SuspensionParams* params);

/// Emits `suspension` and its map (the keys above, in that order, with the comments) into an
/// emitter that is inside a map; the emitter's double precision applies.
void emit_suspension_section(YAML::Emitter& out, const SuspensionParams& params,
                             const FieldComments& comments = {},
                             FieldSelection which = FieldSelection::kAll);

/// The section as YAML text ("suspension:\n  stiffness_n_per_m: ...\n"), numbers with
/// `precision` significant digits (infinities as .inf).
std::string suspension_section_yaml(const SuspensionParams& params,
                                    const FieldComments& comments = {}, int precision = 10);

}  // namespace vmass
