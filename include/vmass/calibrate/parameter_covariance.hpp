// ParameterCovariance: the covariance of a suspension fit's parameters in SI units, and their
// correlation, as vmass-calibrate reports them (calibration_report.hpp).
//
// The fit (suspension_fit.hpp, step 5) gets C = (J^T J)^-1 of the robustified problem from
// ceres::Covariance in its own parameters (z0 [mm], c [N/mm], d [mm], k2 [N/mm^2]) and scales it
// by s^2, the same s the standard deviations are scaled by. The reported parameters are linear
// in the fitted ones, phi = A theta (stiffness = 1e3 c, zero offset = 1e-3 z0, knee = 1e-3 (z0 +
// d), rate = 1e6 k2), so their covariance is
//   Sigma = s^2 A C A^T,          entry (i, j) in unit_i x unit_j,
// and their correlation r_ij = Sigma_ij / sqrt(Sigma_ii Sigma_jj) (scale-free: s and the units
// cancel). sqrt(Sigma_ii) is the parameter's reported std.
//
// make_parameter_covariance() accepts Sigma only when it is a covariance: finite, symmetric,
// positive variances, and a correlation matrix whose smallest eigenvalue is above 1e-12 (else
// some combination of the parameters is not determined by the data: rank deficient). When it is
// not (or when the fit could not compute it: Ceres found J^T J rank deficient, no residual
// degrees of freedom to scale it with), `estimable` is false and `reason` says why; the matrices
// are then empty, never NaN.
//
// Pure functions; thread-safe.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace vmass::calibrate {

struct ParameterCovariance {
  /// The parameters, in matrix order, named as in vmass-calibrate --json with their SI unit
  /// ("stiffness_n_per_m", "zero_offset_m", "knee_m", "rate_n_per_m2").
  std::vector<std::string> names;
  bool estimable = false;
  std::string reason;               ///< why not, when !estimable ("" when estimable)
  std::vector<double> covariance;   ///< Sigma, row-major n x n, SI units (empty when !estimable)
  std::vector<double> correlation;  ///< r, row-major n x n (empty when !estimable)

  std::size_t size() const { return names.size(); }
  double covariance_at(std::size_t i, std::size_t j) const { return covariance[i * size() + j]; }
  double correlation_at(std::size_t i, std::size_t j) const { return correlation[i * size() + j]; }
};

/// A covariance from a row-major n x n matrix in SI units (see the header comment for when it
/// is accepted). The result is exactly symmetric (the mean of Sigma and Sigma^T) with a unit
/// diagonal correlation.
ParameterCovariance make_parameter_covariance(std::vector<std::string> names,
                                              const std::vector<double>& row_major);

/// A covariance that could not be computed, and why.
ParameterCovariance not_estimable_covariance(std::vector<std::string> names, std::string reason);

/// A pair of parameters whose estimates trade off: |r| above the threshold.
struct CorrelatedPair {
  std::size_t first = 0;  ///< index into names, first < second
  std::size_t second = 0;
  double correlation = 0.0;
};

/// The pairs with |r| > threshold, strongest first (none when not estimable).
std::vector<CorrelatedPair> strongly_correlated(const ParameterCovariance& covariance,
                                                double threshold = 0.9);

}  // namespace vmass::calibrate
