#include "vmass/service/state_plausibility.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vmass::service {
namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

/// Accumulates the first reason a state is not believable.
class Check {
 public:
  explicit Check(const VehicleParams& v)
      : min_mass_kg_(0.5 * v.empty_mass_kg),
        max_mass_kg_(std::isfinite(v.max_mass_kg)
                         ? std::max(1.5 * v.max_mass_kg, 5.0 * v.empty_mass_kg)
                         : 5.0 * v.empty_mass_kg) {}

  void finite(const char* what, double v) {
    if (!std::isfinite(v)) fail(std::string(what) + " is " + number(v));
  }
  void positive(const char* what, double v) {
    if (!(std::isfinite(v) && v > 0.0)) fail(std::string(what) + " " + number(v) + " is not > 0");
  }
  void mass(const char* what, double kg) {
    if (!(kg >= min_mass_kg_ && kg <= max_mass_kg_)) {
      fail(std::string(what) + " " + number(kg) + " kg outside [" + number(min_mass_kg_) + ", " +
           number(max_mass_kg_) + "] kg");
    }
  }
  /// A 2x2 covariance, row-major.
  void covariance(const char* what, const double (&c)[4]) {
    for (double x : c) finite(what, x);
    positive(what, c[0]);
    positive(what, c[3]);
    const double scale = std::max({std::abs(c[1]), std::abs(c[2]), 1e-300});
    if (std::abs(c[1] - c[2]) > 1e-9 * scale) fail(std::string(what) + " is not symmetric");
    if (!(c[0] * c[3] - c[1] * c[2] >= -1e-12 * c[0] * c[3])) {
      fail(std::string(what) + " is not positive semi-definite");
    }
  }
  void counter(const char* what, long n) {
    if (n < 0) fail(std::string(what) + " " + std::to_string(n) + " is negative");
  }
  const std::string& reason() const { return reason_; }

 private:
  void fail(const std::string& why) {
    if (reason_.empty()) reason_ = why;
  }
  double min_mass_kg_, max_mass_kg_;
  std::string reason_;
};

void check_regressor(const PipelineSnapshot& s, Check& c) {
  if (s.type == RegressorType::kRls) {
    c.finite("RLS mu", s.rls_theta[1]);
    c.mass("RLS mass", s.rls_theta[0]);
    c.covariance("RLS covariance", s.rls_covariance);
    return;
  }
  c.finite("Bayes mu", s.nig_mean[1]);
  c.mass("Bayes mass", s.nig_mean[0]);
  c.covariance("Bayes scaled covariance", s.nig_scaled_covariance);
  c.positive("Bayes shape", s.nig_shape);
  c.positive("Bayes scale", s.nig_scale);
}

void check_counters(const PipelineSnapshot& s, Check& c) {
  c.counter("pairs used", s.pairs_used);
  for (const BlockCounters& b : s.blocks) {
    c.counter("block ticks", b.ticks);
    c.counter("block candidates", b.candidates);
    c.counter("block accepted pairs", b.accepted);
    c.counter("block rejected pairs", b.rejected_innovation);
    if (b.accepted > b.candidates || b.candidates > b.ticks) {
      c.counter("block counters out of order (accepted <= candidates <= ticks)", -1);
    }
  }
}

}  // namespace

std::string implausible_state(const PipelineSnapshot& s, const PipelineParams& params) {
  Check c(params.vehicle);
  c.mass("prior mass", s.prior.mass_kg);
  c.positive("prior mass std", s.prior.mass_std_kg);
  c.finite("prior mu", s.prior.mu_n);
  c.positive("prior mu std", s.prior.mu_std_n);
  check_regressor(s, c);
  if (s.has_reference) {
    c.finite("reference deflection", s.reference_deflection_m);
    c.finite("reference deflection std", s.reference_deflection_std_m);
  }
  check_counters(s, c);
  return c.reason();
}

}  // namespace vmass::service
