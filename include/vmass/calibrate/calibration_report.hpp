// CalibrationReport: what vmass-calibrate prints and writes from a SuspensionCalibration.
//
//  - suspension_yaml(): the `suspension:` section vmassd's config loader reads (exactly the
//    keys of docs/formats.md: stiffness_n_per_m, empty_deflection_m, progressive_knee_m,
//    progressive_rate_n_per_m2, linear_range_kg, calibrated_range_kg), numbers locale-free with
//    10 significant digits, infinity as .inf, each estimate's std as a trailing comment;
//    check_suspension_yaml() reads it back with the loader's reader, so that a fit the loader
//    would refuse (a unit error in the ballast data) is not written;
//  - mass_check(): per step, the total mass the product's static initialisation (eq. 3,
//    StaticInitializer::mass_from_deflection_kg) gets from the step's mean deflection, once with
//    the linear model and once with the written (progressive) curve, against the true total
//    M_idle + m_k:
//      M_est = M_idle + 2 l F(z_k) / (l_f g),   error = (M_est - M_true) / M_true;
//  - calibration_json(): one JSON object (parameters with std and interval, per-step residuals,
//    ranges, the mass check when given; per model the parameters' correlation and covariance in
//    SI units keyed by parameter name, or why not, and the strongly correlated pairs: keys in
//    docs/formats.md, "Calibration result");
//  - calibration_text(): the same as a human-readable report with per-step tables; per model the
//    correlation and covariance matrices, and for each pair with |r| > 0.9 a line saying that
//    they trade off and what ballast steps would separate them (or that none would: knee and
//    rate), else "none"; a covariance that is not estimable is said with its reason.
//
// Pure functions; thread-safe.
#pragma once

#include <string>
#include <vector>

#include "vmass/calibrate/suspension_fit.hpp"
#include "vmass/core/vehicle_params.hpp"

namespace vmass::calibrate {

struct MassCheckRow {
  double added_mass_kg = 0.0;
  double true_mass_kg = 0.0;
  double deflection_m = 0.0;
  double linear_mass_kg = 0.0;
  double linear_error = 0.0;         ///< relative to the true total
  double progressive_mass_kg = 0.0;  ///< with suspension_params() (the written curve)
  double progressive_error = 0.0;
  bool beyond_linear_range = false;
};

/// Uses vehicle.empty_mass_kg, wheelbase_m, cg_to_front_axle_m and gravity_mps2.
std::vector<MassCheckRow> mass_check(const SuspensionCalibration& calibration,
                                     const VehicleParams& vehicle);

/// The config snippet; header_comment lines (without '#') go on top.
std::string suspension_yaml(const SuspensionCalibration& calibration,
                            const std::vector<std::string>& header_comment = {});

/// "" when vmassd's config loader accepts `yaml` (a suspension_yaml() snippet) as written: every
/// key within the loader's own bound for its unit (YamlReader: |stiffness_n_per_m| <= 1e10 N/m,
/// |progressive_rate_n_per_m2| <= 1e12 N/m^2, ...) and SuspensionParams::validate(); else why
/// not ("suspension.KEY: ..."). A snippet it refuses must never be written.
std::string check_suspension_yaml(const std::string& yaml);

/// One JSON object; mass_rows may be empty (no empty mass known).
std::string calibration_json(const SuspensionCalibration& calibration,
                             const std::vector<MassCheckRow>& mass_rows);

std::string calibration_text(const SuspensionCalibration& calibration,
                             const std::vector<MassCheckRow>& mass_rows);

}  // namespace vmass::calibrate
