#include "vmass/service/state_plausibility.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "vmass/core/learnt_gear_masses.hpp"
#include "vmass/core/learnt_scale.hpp"
#include "vmass/core/pair_term_fit.hpp"
#include "vmass/core/plausible_band.hpp"
#include "vmass/core/static_initializer.hpp"

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
  explicit Check(const VehicleParams& v) : band_(plausible_mass_band(v)) {}

  void finite(const char* what, double v) {
    if (!std::isfinite(v)) fail(std::string(what) + " is " + number(v));
  }
  void positive(const char* what, double v) {
    if (!(std::isfinite(v) && v > 0.0)) fail(std::string(what) + " " + number(v) + " is not > 0");
  }
  void mass(const char* what, double kg) {
    if (!band_.contains(kg)) {
      fail(std::string(what) + " " + number(kg) + " kg outside the plausible band [" +
           number(band_.low_kg) + ", " + number(band_.high_kg) + "] kg");
    }
  }
  /// A regressor's mass variance: no data from a vehicle's dynamics pins a mass closer than
  /// 0.1 % per pair (force and acceleration noise), so after n pairs its std is at least
  /// 0.1 % M / sqrt(n). Below that the state is degenerate: it would publish a zero-width
  /// interval and no pair would ever move it.
  void mass_variance(const char* what, double variance_kg2, double mass_kg, long pairs) {
    const double floor_kg = 1e-3 * std::abs(mass_kg) / std::sqrt(std::max(1.0, double(pairs)));
    if (!(variance_kg2 >= floor_kg * floor_kg)) {
      fail(std::string(what) + " std " + number(std::sqrt(std::max(0.0, variance_kg2))) +
           " kg below the floor " + number(floor_kg) + " kg (0.1 % of the mass / sqrt(pairs))");
    }
  }
  void within(const char* what, double v, double lo, double hi, const char* unit) {
    if (!(v >= lo && v <= hi)) {
      fail(std::string(what) + " " + number(v) + " " + unit + " outside [" + number(lo) + ", " +
           number(hi) + "] " + unit);
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
  void fail(const std::string& why) {
    if (reason_.empty()) reason_ = why;
  }

 private:
  MassBand band_;
  std::string reason_;
};

void check_regressor(const PipelineSnapshot& s, Check& c) {
  if (s.type == RegressorType::kRls) {
    c.finite("RLS mu", s.rls_theta[1]);
    c.mass("RLS mass", s.rls_theta[0]);
    c.covariance("RLS covariance", s.rls_covariance);
    c.mass_variance("RLS mass", s.rls_covariance[0], s.rls_theta[0], s.pairs_used);
    return;
  }
  c.finite("Bayes mu", s.nig_mean[1]);
  c.mass("Bayes mass", s.nig_mean[0]);
  c.covariance("Bayes scaled covariance", s.nig_scaled_covariance);
  c.positive("Bayes shape", s.nig_shape);
  c.positive("Bayes scale", s.nig_scale);
  // The mass's t-scale squared, (b / a) V[0][0].
  c.mass_variance("Bayes mass", s.nig_scale / s.nig_shape * s.nig_scaled_covariance[0],
                  s.nig_mean[0], s.pairs_used);
}

/// The standstill window the load was measured in: its deflection reads (eq. 3, with the
/// payload position's prior, as the pipeline reads it) as a mass in the band, and its grade is a
/// grade (|g sin(grade)| <= g; NaN: unknown).
void check_reference(const PipelineSnapshot& s, const PipelineParams& params, Check& c) {
  if (!s.has_reference) return;
  c.finite("reference deflection", s.reference_deflection_m);
  c.finite("reference deflection std", s.reference_deflection_std_m);
  c.within("reference deflection std", s.reference_deflection_std_m, 0.0, 1.0, "m");
  const StaticInitializer eq3(params.vehicle, params.suspension, params.estimator.static_init);
  c.mass("reference deflection's static mass (eq. 3)",
         eq3.static_mass_for(s.reference_deflection_m, s.reference_deflection_std_m).prior.mass_kg);
  if (!std::isnan(s.reference_grade_accel_mps2)) {
    const double g = params.vehicle.gravity_mps2;
    c.within("reference grade acceleration", s.reference_grade_accel_mps2, -g, g, "m/s^2");
  }
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

/// What was learnt about the car, and the known mass of the load.
void check_learnt(const PipelineSnapshot& s, const PipelineParams& params, Check& c) {
  const LearningParams& learning = params.estimator.learning;
  if (s.learnt_saved) {
    const LearntScale prior(learning, std::sqrt(declared_scale_variance(params.vehicle)));
    if (std::string why = prior.implausible(s.learnt); !why.empty()) c.fail(why);
  }
  if (s.gear_masses_saved) {
    const LearntGearMasses gears =
        learnt_gear_masses_for(params.vehicle, learning, params.estimator.model_error_std_fraction);
    if (std::string why = gears.implausible(s.gear_masses); !why.empty()) c.fail(why);
  }
  if (std::string why = PairTermSums::implausible(s.pair_term_sums); !why.empty()) c.fail(why);
  if (std::string why = TyreWatch::implausible(s.tyre_watch); !why.empty()) c.fail(why);
  c.within("pair scale", s.pair_scale, std::exp(-learning.max_abs_log_scale),
           std::exp(learning.max_abs_log_scale), "");
  if (!s.known_mass.active) return;
  c.mass("known mass", s.known_mass.mass_kg);
  c.positive("known mass std", s.known_mass.std_kg);
  c.within("known mass's scale", s.known_mass.scale_used, std::exp(-learning.max_abs_log_scale),
           std::exp(learning.max_abs_log_scale), "");
}

}  // namespace

std::string implausible_state(const PipelineSnapshot& s, const PipelineParams& params) {
  Check c(params.vehicle);
  c.mass("prior mass", s.prior.mass_kg);
  c.positive("prior mass std", s.prior.mass_std_kg);
  c.finite("prior mu", s.prior.mu_n);
  c.positive("prior mu std", s.prior.mu_std_n);
  check_regressor(s, c);
  check_reference(s, params, c);
  check_counters(s, c);
  check_learnt(s, params, c);
  return c.reason();
}

}  // namespace vmass::service
