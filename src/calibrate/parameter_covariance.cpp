#include "vmass/calibrate/parameter_covariance.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include <Eigen/Dense>

namespace vmass::calibrate {
namespace {

// Below this smallest eigenvalue of the correlation matrix (whose eigenvalues sum to n), some
// combination of the parameters has no variance of its own: rank deficient.
constexpr double kMinCorrelationEigenvalue = 1e-12;

// Relative asymmetry accepted before symmetrising (rounding of A C A^T).
constexpr double kSymmetryTolerance = 1e-9;

}  // namespace

ParameterCovariance not_estimable_covariance(std::vector<std::string> names, std::string reason) {
  ParameterCovariance c;
  c.names = std::move(names);
  c.reason = std::move(reason);
  return c;
}

ParameterCovariance make_parameter_covariance(std::vector<std::string> names,
                                              const std::vector<double>& row_major) {
  const std::size_t n = names.size();
  if (n == 0 || row_major.size() != n * n) {
    return not_estimable_covariance(std::move(names), "no covariance matrix of the right size");
  }
  const int size = static_cast<int>(n);
  Eigen::MatrixXd sigma(size, size);
  for (int i = 0; i < size; ++i) {
    for (int j = 0; j < size; ++j) {
      sigma(i, j) = row_major[static_cast<std::size_t>(i) * n + static_cast<std::size_t>(j)];
    }
  }
  if (!sigma.allFinite()) {
    return not_estimable_covariance(std::move(names), "the covariance has non-finite entries");
  }
  for (int i = 0; i < size; ++i) {
    if (!(sigma(i, i) > 0.0)) {
      std::string why =
          "rank deficient: " + names[static_cast<std::size_t>(i)] + " has no variance";
      return not_estimable_covariance(std::move(names), std::move(why));
    }
  }
  const Eigen::VectorXd sd = sigma.diagonal().cwiseSqrt();
  for (int i = 0; i < size; ++i) {
    for (int j = i + 1; j < size; ++j) {
      if (std::abs(sigma(i, j) - sigma(j, i)) > kSymmetryTolerance * sd(i) * sd(j)) {
        return not_estimable_covariance(std::move(names), "the covariance is not symmetric");
      }
    }
  }
  sigma = 0.5 * (sigma + sigma.transpose()).eval();
  Eigen::MatrixXd r(size, size);  // elementwise: exactly symmetric, as sigma is
  for (int i = 0; i < size; ++i) {
    for (int j = 0; j < size; ++j) r(i, j) = i == j ? 1.0 : sigma(i, j) / (sd(i) * sd(j));
  }
  const double smallest =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(r).eigenvalues().minCoeff();
  if (!(smallest > kMinCorrelationEigenvalue)) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%.3g", smallest);
    return not_estimable_covariance(
        std::move(names),
        std::string("rank deficient: a combination of the parameters is not determined by the "
                    "steps (smallest eigenvalue of the correlation matrix ") +
            buf + ")");
  }
  ParameterCovariance c;
  c.names = std::move(names);
  c.estimable = true;
  c.covariance.resize(n * n);
  c.correlation.resize(n * n);
  for (int i = 0; i < size; ++i) {
    for (int j = 0; j < size; ++j) {
      const std::size_t k = static_cast<std::size_t>(i) * n + static_cast<std::size_t>(j);
      c.covariance[k] = sigma(i, j);
      c.correlation[k] = std::clamp(r(i, j), -1.0, 1.0);
    }
  }
  return c;
}

std::vector<CorrelatedPair> strongly_correlated(const ParameterCovariance& covariance,
                                                double threshold) {
  std::vector<CorrelatedPair> pairs;
  if (!covariance.estimable) return pairs;
  for (std::size_t i = 0; i < covariance.size(); ++i) {
    for (std::size_t j = i + 1; j < covariance.size(); ++j) {
      const double r = covariance.correlation_at(i, j);
      if (std::abs(r) > threshold) pairs.push_back({i, j, r});
    }
  }
  std::stable_sort(pairs.begin(), pairs.end(),
                   [](const CorrelatedPair& a, const CorrelatedPair& b) {
                     return std::abs(a.correlation) > std::abs(b.correlation);
                   });
  return pairs;
}

}  // namespace vmass::calibrate
