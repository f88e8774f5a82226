// vmass-numerics: the estimator's numerics under abuse, as a command (issue 11: these take
// minutes, too long for CI under sanitizers). On a recorded drive (samples.csv and its config,
// e.g. from `vmass-sim --scenario paper_exp2 --out DIR`), three checks on core::Pipeline:
//
//   quiet     the drive, then --hours of driving without excitation (a 20 m/s cruise, each
//             input with a sensor's noise): the regressor's covariance stays finite and within
//             2x of where it was, and the estimate within 1 % of the drive's
//   spikes    one sample of one input at a million times that input's largest value on the
//             drive (each input, at 1/4, 1/2 and 3/4 of the drive): the final estimate moves
//             by under 0.5 %
//   poison    the drive repeated for --steps ticks, 1 % of them with one input (drawn at
//             random, flagged valid) NaN, +-infinity or +-denormal (seeded by --seed): no
//             published number is ever non-finite or denormal
//
//   vmass-numerics --config FILE --samples CSV [--estimator rls|bayes] [--hours 24]
//                  [--steps 10000000] [--seed 1]      (--seed: the cruise's noise, the poison)
//
// Prints each check's figures; exit 0 when all three hold, 1 when one fails, 2 on a usage,
// config or input error (tools/common/exit_code.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "exit_code.hpp"
#include "vmass/config/config.hpp"
#include "vmass/core/pipeline.hpp"
#include "vmass/csv/samples_csv.hpp"

using vmass::Estimate;
using vmass::Input;
using vmass::Pipeline;
using vmass::PipelineParams;
using vmass::Sample;
using vmass::tools::kExitFailure;
using vmass::tools::kExitOk;
using vmass::tools::kExitUsage;

namespace {

struct Options {
  std::string config_path, samples_path, estimator;
  double hours = 24.0;
  long steps = 10'000'000;
  unsigned seed = 1;
};

struct Drive {
  PipelineParams params;
  std::vector<Sample> samples;
  double tick_s = 0.01;
};

constexpr std::array<Input, 8> kNumericInputs = {Input::kWheelTorque,
                                                 Input::kBrakePressure,
                                                 Input::kAccelX,
                                                 Input::kAccelY,
                                                 Input::kYawRate,
                                                 Input::kSpeed,
                                                 Input::kSteeringWheelAngle,
                                                 Input::kRearRightDeflection};

double& field(Sample& s, Input in) {
  switch (in) {
    case Input::kWheelTorque:
      return s.wheel_torque_nm;
    case Input::kBrakePressure:
      return s.brake_pressure_pa;
    case Input::kAccelX:
      return s.accel_x_mps2;
    case Input::kAccelY:
      return s.accel_y_mps2;
    case Input::kYawRate:
      return s.yaw_rate_radps;
    case Input::kSpeed:
      return s.speed_mps;
    case Input::kSteeringWheelAngle:
      return s.steering_wheel_angle_rad;
    default:
      return s.rear_right_deflection_m;
  }
}

std::optional<int> parse_options(int argc, char** argv, Options* o) {
  CLI::App app{"vmass-numerics: the estimator's numerics under abuse (quiet, spikes, poison)"};
  app.add_option("--config", o->config_path, "vmass YAML config of the drive")->required();
  app.add_option("--samples", o->samples_path, "samples CSV of the drive")->required();
  app.add_option("--estimator", o->estimator, "override estimator.type")
      ->check(CLI::IsMember({"rls", "bayes"}));
  app.add_option("--hours", o->hours, "hours without excitation after the drive (default 24)")
      ->check(CLI::Range(0.0, 1000.0));
  app.add_option("--steps", o->steps, "ticks of the poison check (default 10000000)")
      ->check(CLI::Range(1L, 1'000'000'000L));
  app.add_option("--seed", o->seed, "seed of the poison check (default 1)");
  return vmass::tools::parse_command_line(app, argc, argv);
}

std::optional<Drive> load_drive(const Options& o) {
  const vmass::ConfigLoad c = vmass::load_config(o.config_path);
  if (!c.ok()) {
    std::cerr << "vmass-numerics: " << c.error << "\n";
    return std::nullopt;
  }
  Drive d;
  d.params = c.config->pipeline;
  if (!o.estimator.empty()) {
    d.params.estimator.type =
        o.estimator == "rls" ? vmass::RegressorType::kRls : vmass::RegressorType::kBayes;
  }
  d.tick_s = 1.0 / d.params.estimator.differencing.tick_rate_hz;
  vmass::SamplesCsvReader reader(o.samples_path);
  if (!reader.error().empty()) {
    std::cerr << "vmass-numerics: " << reader.error() << "\n";
    return std::nullopt;
  }
  while (std::optional<Sample> s = reader.next()) d.samples.push_back(*s);
  if (!reader.read_error().empty() || d.samples.size() < 1000) {
    std::cerr << "vmass-numerics: " << o.samples_path << ": "
              << (reader.read_error().empty() ? "fewer than 1000 samples" : reader.read_error())
              << "\n";
    return std::nullopt;
  }
  return d;
}

/// The drive through a fresh pipeline; the open batch flushed; the final mass.
double final_mass(const Drive& d, const std::vector<Sample>& samples) {
  Pipeline p(d.params);
  for (const Sample& s : samples) p.step(s);
  p.flush();
  return p.estimate().mass_kg;
}

/// Sum of the variances of the regressor's belief (RLS P or the NIG scaled covariance).
double covariance_trace(const Pipeline& p) {
  const vmass::PipelineSnapshot s = p.snapshot();
  return s.type == vmass::RegressorType::kRls
             ? s.rls_covariance[0] + s.rls_covariance[3]
             : s.nig_scaled_covariance[0] + s.nig_scaled_covariance[3];
}

/// A 20 m/s cruise: nothing that excites the estimator, each input with a sensor's noise.
class QuietCruise {
 public:
  QuietCruise(const Sample& last, unsigned seed) : rng_(seed), s_(last) {
    s_.valid = vmass::kAllInputs;
    s_.brake_pressure_pa = 0.0;
    s_.gear = std::max(s_.gear, 1);
  }
  const Sample& at(vmass::TimeUs t) {
    s_.time_us = t;
    s_.wheel_torque_nm = 400.0 + 5.0 * noise_(rng_);
    s_.accel_x_mps2 = 0.02 * noise_(rng_);
    s_.accel_y_mps2 = 0.02 * noise_(rng_);
    s_.yaw_rate_radps = 0.001 * noise_(rng_);
    s_.speed_mps = 20.0 + 0.01 * noise_(rng_);
    s_.steering_wheel_angle_rad = 0.001 * noise_(rng_);
    return s_;
  }

 private:
  std::mt19937_64 rng_;
  std::normal_distribution<double> noise_{0.0, 1.0};
  Sample s_;
};

bool check_quiet(const Drive& d, double hours, unsigned seed) {
  Pipeline p(d.params);
  for (const Sample& s : d.samples) p.step(s);
  const double m0 = p.estimate().mass_kg;
  const long pairs0 = p.estimate().pairs_used;
  const double trace0 = covariance_trace(p);
  QuietCruise cruise(d.samples.back(), seed);
  const auto ticks = static_cast<long>(hours * 3600.0 / d.tick_s);
  const vmass::TimeUs t0 = d.samples.back().time_us;
  double worst_dev = 0.0, worst_growth = 1.0;
  bool finite = true;
  for (long k = 1; k <= ticks; ++k) {
    p.step(cruise.at(t0 + std::llround(static_cast<double>(k) * d.tick_s * 1e6)));
    if (k % 1000 != 0 && k != ticks) continue;
    const double trace = covariance_trace(p);
    finite = finite && std::isfinite(trace) && std::isfinite(p.estimate().mass_kg);
    worst_dev = std::max(worst_dev, std::abs(p.estimate().mass_kg - m0) / m0);
    worst_growth = std::max(worst_growth, trace0 > 0.0 ? trace / trace0 : 1.0);
  }
  const bool ok = finite && worst_dev < 0.01 && worst_growth <= 2.0;
  std::printf(
      "quiet:  %.0f h (%ld ticks) of a noisy 20 m/s cruise after the drive (%.1f kg, %ld "
      "pairs; %ld pairs more): estimate within %.4f %%, covariance trace at most %.4fx its "
      "start%s -> %s\n",
      hours, ticks, m0, pairs0, p.estimate().pairs_used - pairs0, 100.0 * worst_dev, worst_growth,
      finite ? "" : ", NOT FINITE", ok ? "ok" : "FAILED");
  return ok;
}

bool check_spikes(const Drive& d) {
  const double clean = final_mass(d, d.samples);
  double worst = 0.0;
  std::string worst_what;
  for (const Input in : kNumericInputs) {
    double worst_here = 0.0;
    double largest = 0.0;
    for (Sample s : d.samples) largest = std::max(largest, std::abs(field(s, in)));
    if (largest == 0.0) largest = 1.0;
    for (const double at : {0.25, 0.5, 0.75}) {
      std::vector<Sample> spiked = d.samples;
      const auto k = static_cast<std::size_t>(at * static_cast<double>(spiked.size()));
      field(spiked[k], in) = 1e6 * largest;
      spiked[k].valid |= vmass::input_bit(in);
      const double dev = std::abs(final_mass(d, spiked) - clean) / clean;
      worst_here = std::max(worst_here, dev);
      if (dev >= worst) {
        worst = dev;
        worst_what = std::string(vmass::input_name(in)) + " at " + std::to_string(at);
      }
    }
    std::printf("  spike of %s (1e6 x %g): final estimate moved by at most %.4f %%\n",
                std::string(vmass::input_name(in)).c_str(), largest, 100.0 * worst_here);
  }
  const bool ok = worst < 0.005;
  std::printf(
      "spikes: 24 single spikes of 1e6x (8 inputs x 3 times), final %.1f kg clean: "
      "largest move %.4f %% (%s) -> %s\n",
      clean, 100.0 * worst, worst_what.c_str(), ok ? "ok" : "FAILED");
  return ok;
}

bool publishable(double v) {
  return std::isfinite(v) && (v == 0.0 || std::fpclassify(v) == FP_NORMAL);
}

bool estimate_ok(const Estimate& e) {
  return publishable(e.mass_kg) && publishable(e.mu_n) && publishable(e.mass_std_kg) &&
         publishable(e.ci_low_kg) && publishable(e.ci_high_kg) && publishable(e.initial_mass_kg);
}

bool check_poison(const Drive& d, long steps, unsigned seed) {
  constexpr double kDenormal = std::numeric_limits<double>::denorm_min() * 3.0;
  const std::array<double, 5> poisons = {
      std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
      -std::numeric_limits<double>::infinity(), kDenormal, -kDenormal};
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_int_distribution<std::size_t> pick_input(0, kNumericInputs.size() - 1);
  std::uniform_int_distribution<std::size_t> pick_poison(0, poisons.size() - 1);
  Pipeline p(d.params);
  const vmass::TimeUs lap_us = d.samples.back().time_us - d.samples.front().time_us +
                               static_cast<vmass::TimeUs>(std::llround(d.tick_s * 1e6));
  long poisoned = 0, bad = 0, first_bad = -1;
  for (long k = 0; k < steps; ++k) {
    const auto n = static_cast<long>(d.samples.size());
    Sample s = d.samples[static_cast<std::size_t>(k % n)];
    s.time_us += (k / n) * lap_us;
    if (unit(rng) < 0.01) {
      const Input in = kNumericInputs[pick_input(rng)];
      field(s, in) = poisons[pick_poison(rng)];
      s.valid |= vmass::input_bit(in);
      ++poisoned;
    }
    p.step(s);
    if (p.estimate().mass_known && !estimate_ok(p.estimate())) {
      if (first_bad < 0) first_bad = k;
      ++bad;
    }
  }
  const bool ok = bad == 0;
  const std::string first =
      bad == 0 ? "" : " (the first at tick " + std::to_string(first_bad) + ")";
  std::printf(
      "poison: %ld ticks, %ld poisoned (NaN, +-inf, +-denormal): %ld estimates with a "
      "non-finite or denormal number%s; last %.1f kg -> %s\n",
      steps, poisoned, bad, first.c_str(), p.estimate().mass_kg, ok ? "ok" : "FAILED");
  return ok;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (const auto code = parse_options(argc, argv, &o)) return *code;
  const std::optional<Drive> d = load_drive(o);
  if (!d) return kExitUsage;
  std::printf("vmass-numerics: %s, %zu samples, %s estimator\n", o.samples_path.c_str(),
              d->samples.size(),
              std::string(vmass::regressor_type_name(d->params.estimator.type)).c_str());
  std::fflush(stdout);
  const bool quiet = check_quiet(*d, o.hours, o.seed);
  std::fflush(stdout);
  const bool spikes = check_spikes(*d);
  std::fflush(stdout);
  const bool poison = check_poison(*d, o.steps, o.seed);
  return quiet && spikes && poison ? kExitOk : kExitFailure;
}
