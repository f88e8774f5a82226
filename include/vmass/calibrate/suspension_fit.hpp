// SuspensionFit: the rear-right suspension stiffness from static ballast steps, with Ceres.
//
// Mass to force (load_geometry.hpp, paper eq. 2): each step's added rear-right wheel force is
//   F_k = m_k g l_f / (2 l).
// Models (residuals in suspension_residuals.hpp, deflection errors in mm):
//   linear (eq. 3):  z = z0 + F / c
//   progressive:     F = c (z - z0) + k2 max(0, z - z_knee)^2   (SuspensionParams::wheel_force_n)
//
// Procedure of fit_suspension():
//  1. check_steps() (>= 3 distinct loads, finite, deflection strictly increasing with load).
//  2. Robust loss: Cauchy, rho(s) = a^2 log(1 + s / a^2), so that one bad step is down-weighted
//     instead of bending the fit. The scale a is `robust_scale_mm` when given, else it is
//     re-estimated from the residuals, a = max(min_robust_scale_mm, 3 * 1.4826 median|r|
//     sqrt(n / (n - p))) (three robust sigmas, corrected for the p parameters the fit absorbs),
//     and the fit repeated until a settles (at most 6 passes, starting from 1 % of the
//     deflection range). The floor keeps steps from being called outliers for residuals below
//     what a deflection sensor resolves.
//  3. Progressive model, when there are >= min_steps_below_knee + min_steps_beyond_knee steps.
//     The knee makes the cost non-smooth in z_knee (second derivatives jump whenever the knee
//     crosses a step), so the knee is found on a grid and then refined: for each gap between
//     consecutive step deflections that leaves enough steps on both sides, knee_grid_per_gap
//     knee offsets d inside the gap are tried with d held constant (a smooth problem in z0, c,
//     k2: no step changes side), the best is kept and all four parameters are then refined
//     together from there (the cost is C1, see the residual header, and LM starts next to its
//     minimum). We do not use a smooth surrogate (softplus^2 with a sharpness): it would fit a
//     rounded curve whose knee and rate are biased relative to the hard max() curve that the
//     config stores and the static initialisation inverts.
//     The bump stop is accepted when k2 > 0, at least min_steps_beyond_knee steps lie beyond
//     the knee, it moves the top step by more than 2 a, and the progressive model explains
//     the data significantly better than the linear model over all steps: with robust costs C
//     at the same scale, F = ((C_lin - C_prog) / 2) / (C_prog / (n - 4)) > F-quantile(1 - alpha; 2,
//     n - 4), alpha = progressive_significance.
//  4. Linear model: fitted on the steps at or below the knee (all steps without a bump stop).
//  5. Uncertainty: ceres::Covariance (dense SVD) gives (J^T J)^-1 of the robustified problem at
//     the solution; it is scaled by s^2 = max(sum w_k r_k^2 / (sum w_k - p), se^2), w_k =
//     rho'(r_k^2) the Cauchy weights, p the parameter count, se^2 = sum w_k se_k^2 / sum w_k the
//     steps' own squared standard errors (se_k = s_k / sqrt(n_k) from their samples; 0 for a
//     one-sample step): with few steps the residuals alone can be luckily small, and the scatter
//     of the step means cannot be smaller than their sampling noise. Intervals are
//     value +- t_{(1+confidence)/2, sum w - p} std (Student t). Every solve must pass
//     Summary::IsSolutionUsable(). The same scaled matrix, carried to the reported parameters in
//     SI units (the knee is z0 + d), is each fit's `covariance` with its correlation
//     (parameter_covariance.hpp): linear (stiffness, zero offset), progressive (stiffness, zero
//     offset, knee, rate; only for an accepted bump stop). Not estimable, with the reason, when
//     Ceres finds J^T J rank deficient or there is no residual degree of freedom to scale by.
//  6. Steps with |r| > 2 a (weight < 0.2) are reported as outliers.
//  7. Linear range: the largest added load m_k such that every non-outlier step with
//     0 < m <= m_k is reproduced by the linear model within linear_tolerance:
//       |2 l c (z - z0) / (l_f g) - m| <= linear_tolerance * m.
//     The calibrated range is the largest added load of the test.
//
// Thread-safety: fit_suspension() has no shared state; concurrent calls are safe.
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "vmass/calibrate/ballast_step.hpp"
#include "vmass/calibrate/load_geometry.hpp"
#include "vmass/calibrate/parameter_covariance.hpp"
#include "vmass/core/vehicle_params.hpp"

namespace vmass::calibrate {

struct SuspensionFitOptions {
  double linear_tolerance = 0.01;          ///< linear range: relative error of the added load
  double robust_scale_mm = 0.0;            ///< Cauchy scale a; 0: estimated from the residuals
  double min_robust_scale_mm = 0.01;       ///< floor of a (sensor resolution), mm
  int knee_grid_per_gap = 8;               ///< knee candidates between two step deflections
  int min_steps_below_knee = 3;            ///< the linear part must keep its own uncertainty
  int min_steps_beyond_knee = 2;           ///< d and k2 need two steps beyond the knee
  double progressive_significance = 0.01;  ///< alpha of the F test
  double confidence = 0.95;                ///< level of the reported intervals

  /// "" or a message naming the key (fit.*) and the violated bound.
  std::string validate() const;
};

/// A fitted parameter with its standard deviation and interval (NaN when not estimable).
struct Estimate {
  double value = std::numeric_limits<double>::quiet_NaN();
  double std = std::numeric_limits<double>::quiet_NaN();
  double low = std::numeric_limits<double>::quiet_NaN();
  double high = std::numeric_limits<double>::quiet_NaN();
};

struct FitStats {
  int steps_used = 0;
  double robust_scale_mm = 0.0;  ///< Cauchy a of the final pass
  double residual_std_mm = 0.0;  ///< from the residuals
  double step_se_mm = 0.0;       ///< RMS standard error of the step means (0: unknown)
  double effective_dof = 0.0;    ///< sum w - p
  double cost = 0.0;             ///< Ceres' final cost (robust)
  int iterations = 0;            ///< of the final solve
  std::string termination;       ///< of the final solve
};

struct LinearFit {
  Estimate stiffness_n_per_m;  ///< c
  Estimate zero_offset_m;      ///< z0: the sensor reading at zero added load
  FitStats stats;
  ParameterCovariance covariance;  ///< stiffness_n_per_m, zero_offset_m
};

struct ProgressiveFit {
  bool detected = false;       ///< bump stop significant (step 3); else the fields below
  std::string reason;          ///<   hold the best progressive fit tried, or nothing
  Estimate stiffness_n_per_m;  ///< c (below the knee)
  Estimate zero_offset_m;      ///< z0
  Estimate knee_m;             ///< z_knee = z0 + d, sensor coordinates
  Estimate rate_n_per_m2;      ///< k2
  double f_statistic = std::numeric_limits<double>::quiet_NaN();
  double f_critical = std::numeric_limits<double>::quiet_NaN();
  FitStats stats;
  /// stiffness_n_per_m, zero_offset_m, knee_m, rate_n_per_m2 (not estimable without a bump stop)
  ParameterCovariance covariance;
};

/// How the fit describes one ballast step (the calibration report's per-step row).
struct BallastStepFit {
  BallastStep step;
  double force_n = 0.0;            ///< F_k
  double linear_residual_m = 0.0;  ///< z_meas - z_linear(F)
  double progressive_residual_m = std::numeric_limits<double>::quiet_NaN();
  bool in_linear_fit = false;      ///< at or below the knee
  bool outlier = false;            ///< of the model that describes this step
  double linear_mass_error = 0.0;  ///< (m_linear(z) - m) / m; 0 for m = 0
};

struct SuspensionCalibration {
  LoadGeometry geometry;
  LinearFit linear;
  ProgressiveFit progressive;
  std::vector<BallastStepFit> steps;  ///< sorted by added mass
  double linear_range_kg = 0.0;
  double calibrated_range_kg = 0.0;
  double linear_tolerance = 0.01;
  std::vector<std::string> warnings;

  /// The suspension section to write: the progressive curve when detected (one consistent
  /// curve: its c, z0, knee and rate), else the linear model; plus both ranges.
  SuspensionParams suspension_params() const;
  /// The linear model alone (no knee), for comparison.
  SuspensionParams linear_suspension_params() const;
};

struct SuspensionFitResult {
  std::optional<SuspensionCalibration> calibration;
  std::string error;  ///< bad data, bad options or a fit Ceres could not make usable
  bool ok() const { return calibration.has_value(); }
};

SuspensionFitResult fit_suspension(const std::vector<BallastStep>& steps,
                                   const LoadGeometry& geometry,
                                   const SuspensionFitOptions& options = {});

}  // namespace vmass::calibrate
