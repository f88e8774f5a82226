#include "vmass/calibrate/plateau_detector.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "vmass/core/param_check.hpp"

namespace vmass::calibrate {
namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const std::size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid), v.end());
  double m = v[mid];
  if (v.size() % 2 == 0) {
    m = 0.5 * (m + *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid)));
  }
  return m;
}

std::string span(double a_s, double b_s) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.2f-%.2f s", a_s, b_s);
  return buf;
}

// Sums of (z - ref) over kept samples, to merge plateaus exactly.
struct Accumulator {
  double start_s = 0.0;
  double end_s = 0.0;
  double sum = 0.0;
  double sum_sq = 0.0;
  long count = 0;
  double mean(double ref) const { return ref + sum / static_cast<double>(count); }
  double std() const {
    if (count < 2) return 0.0;
    const double n = static_cast<double>(count);
    return std::sqrt(std::max(0.0, (sum_sq - sum * sum / n) / (n - 1.0)));
  }
};

}  // namespace

std::string PlateauParams::validate() const {
  ParamCheck c("plateau");
  c.non_negative("standstill_speed_mps", standstill_speed_mps);
  c.positive("window_s", window_s);
  c.positive("steady_std_factor", steady_std_factor);
  c.positive("steady_drift_sigma", steady_drift_sigma);
  c.positive("min_noise_m", min_noise_m);
  c.non_negative("settle_s", settle_s);
  c.positive("min_plateau_s", min_plateau_s);
  c.positive("min_step_m", min_step_m);
  return c.message();
}

namespace {

/// "" when every sample is finite and the times increase, else which sample is not.
std::string check_series(const std::vector<DeflectionPoint>& series) {
  const std::size_t n = series.size();
  if (n < 3) return "the deflection series has " + std::to_string(n) + " samples; too few";
  for (std::size_t i = 0; i < n; ++i) {
    const DeflectionPoint& p = series[i];
    if (!std::isfinite(p.time_s) || !std::isfinite(p.deflection_m)) {
      return "sample " + std::to_string(i) + ": time or deflection is NaN or infinite";
    }
    if (i > 0 && !(p.time_s > series[i - 1].time_s)) {
      return "sample " + std::to_string(i) + ": time " + std::to_string(p.time_s) +
             " s does not increase (previous " + std::to_string(series[i - 1].time_s) + " s)";
    }
  }
  return "";
}

/// The series with what the steps below ask of it in O(1): standing flags, the sample period,
/// prefix sums (relative to the first sample, for accuracy), moving-sample and gap counts.
struct Series {
  Series(const std::vector<DeflectionPoint>& points, const PlateauParams& params) : at(points) {
    const std::size_t n = points.size();
    standing.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const double v = points[i].speed_mps;
      standing[i] = std::isnan(v) || std::abs(v) <= params.standstill_speed_mps;
    }
    std::vector<double> dts;
    dts.reserve(n - 1);
    for (std::size_t i = 1; i < n; ++i) dts.push_back(points[i].time_s - points[i - 1].time_s);
    dt_s = median(dts);
    gap_s = std::max(5.0 * dt_s, 0.0);
    ref = points[0].deflection_m;
    s1.assign(n + 1, 0.0);
    s2.assign(n + 1, 0.0);
    moving.assign(n + 1, 0);
    gaps.assign(n + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
      const double z = points[i].deflection_m - ref;
      s1[i + 1] = s1[i] + z;
      s2[i + 1] = s2[i] + z * z;
      moving[i + 1] = moving[i] + (standing[i] ? 0 : 1);
      gaps[i + 1] = gaps[i] + ((i > 0 && points[i].time_s - points[i - 1].time_s > gap_s) ? 1 : 0);
    }
  }
  std::size_t size() const { return at.size(); }
  double time(std::size_t i) const { return at[i].time_s; }
  /// Mean of (z - ref) over samples lo..hi (inclusive).
  double window_mean(std::size_t lo, std::size_t hi) const {
    return (s1[hi + 1] - s1[lo]) / static_cast<double>(hi - lo + 1);
  }

  const std::vector<DeflectionPoint>& at;
  std::vector<char> standing;
  double dt_s = 0.0, gap_s = 0.0, ref = 0.0;
  std::vector<double> s1, s2;
  std::vector<long> moving, gaps;
};

/// 1. The noise, from the first differences of standing samples (robust: MAD).
double noise_std(const Series& s, const PlateauParams& params) {
  std::vector<double> diffs;
  diffs.reserve(s.size() - 1);
  for (std::size_t i = 1; i < s.size(); ++i) {
    if (s.standing[i] && s.standing[i - 1]) {
      diffs.push_back(std::abs(s.at[i].deflection_m - s.at[i - 1].deflection_m));
    }
  }
  return std::max(params.min_noise_m, 1.4826 * median(diffs) / std::sqrt(2.0));
}

/// 2. Steady samples: the window around each is standing, without a gap, with a spread of at
/// most steady_std_factor sigma and no drift.
std::vector<char> steady_samples(const Series& s, double sigma, const PlateauParams& params) {
  const std::size_t n = s.size();
  const double half = 0.5 * params.window_s;
  std::vector<char> steady(n, 0);
  std::size_t lo = 0, hi = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = s.time(i);
    if (t - half < s.time(0) || t + half > s.time(n - 1)) continue;
    while (s.time(lo) < t - half) ++lo;
    if (hi < i) hi = i;
    while (hi + 1 < n && s.time(hi + 1) <= t + half) ++hi;
    if (hi - lo + 1 < 3) continue;
    if (s.moving[hi + 1] - s.moving[lo] > 0) continue;
    if (s.gaps[hi + 1] - s.gaps[lo + 1] > 0) continue;  // a gap between two window samples
    const double count = static_cast<double>(hi - lo + 1);
    const double sum = s.s1[hi + 1] - s.s1[lo];
    const double var = std::max(0.0, (s.s2[hi + 1] - s.s2[lo] - sum * sum / count) / (count - 1.0));
    // No drift: the means of the window's two halves agree within steady_drift_sigma of
    // their difference's std, 2 sigma / sqrt(count) (a slow ramp passes the std test alone).
    const std::size_t mid = lo + (hi - lo) / 2;
    const double drift = s.window_mean(mid + 1, hi) - s.window_mean(lo, mid);
    steady[i] = std::sqrt(var) <= params.steady_std_factor * sigma &&
                std::abs(drift) <= params.steady_drift_sigma * 2.0 * sigma / std::sqrt(count);
  }
  return steady;
}

/// 3.-4. The steady run a..b trimmed of its settling transient: the first sample from which a
/// window's mean is at the run's level (the median of its second half). b + 1 when none.
std::size_t settled_start(const Series& s, std::size_t a, std::size_t b, double sigma,
                          const PlateauParams& params) {
  const std::size_t window_n =
      std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(params.window_s / s.dt_s)));
  const double level_tolerance = 3.0 * sigma / std::sqrt(static_cast<double>(window_n));
  std::size_t k = a;
  while (k <= b && s.time(k) < s.time(a) + params.settle_s) ++k;
  if (k > b) return k;  // shorter than the settling time (typically inside a ramp)
  std::vector<double> second_half;
  for (std::size_t j = k + (b - k) / 2; j <= b; ++j) second_half.push_back(s.at[j].deflection_m);
  const double level = median(second_half) - s.ref;
  while (k <= b) {
    const std::size_t end = std::min(b, k + window_n - 1);
    if (std::abs(s.window_mean(k, end) - level) <= level_tolerance) break;
    ++k;
  }
  return k;
}

Accumulator accumulate(const Series& s, std::size_t k, std::size_t b) {
  Accumulator acc;
  acc.start_s = s.time(k);
  acc.end_s = s.time(b);
  for (std::size_t j = k; j <= b; ++j) {
    const double z = s.at[j].deflection_m - s.ref;
    acc.sum += z;
    acc.sum_sq += z * z;
    ++acc.count;
  }
  return acc;
}

/// 3.-5. The steady runs, trimmed, too short ones dropped, neighbours closer than min_step_m
/// merged.
std::vector<Accumulator> plateau_sums(const Series& s, const std::vector<char>& steady,
                                      double sigma, const PlateauParams& params,
                                      std::vector<std::string>* notes) {
  std::vector<Accumulator> kept;
  std::size_t i = 0;
  while (i < s.size()) {
    if (!steady[i]) {
      ++i;
      continue;
    }
    std::size_t b = i;
    while (b + 1 < s.size() && steady[b + 1] && s.time(b + 1) - s.time(b) <= s.gap_s) ++b;
    const std::size_t a = i;
    i = b + 1;
    const std::size_t k = settled_start(s, a, b, sigma, params);
    if (s.time(a) + params.settle_s > s.time(b) && k > b) continue;  // inside a ramp
    if (k > b || s.time(b) - s.time(k) < params.min_plateau_s) {
      notes->push_back("steady run " + span(s.time(a), s.time(b)) +
                       " shorter than plateau.min_plateau_s after settling; ignored");
      continue;
    }
    const Accumulator acc = accumulate(s, k, b);
    if (!kept.empty() && std::abs(kept.back().mean(s.ref) - acc.mean(s.ref)) < params.min_step_m) {
      Accumulator& prev = kept.back();
      notes->push_back("plateaus " + span(prev.start_s, prev.end_s) + " and " +
                       span(acc.start_s, acc.end_s) +
                       " differ by less than plateau.min_step_m; merged");
      prev.end_s = acc.end_s;
      prev.sum += acc.sum;
      prev.sum_sq += acc.sum_sq;
      prev.count += acc.count;
      continue;
    }
    kept.push_back(acc);
  }
  return kept;
}

}  // namespace

PlateauDetection detect_plateaus(const std::vector<DeflectionPoint>& series,
                                 const PlateauParams& params) {
  PlateauDetection out;
  out.error = params.validate();
  if (out.error.empty()) out.error = check_series(series);
  if (!out.error.empty()) return out;
  const Series s(series, params);
  const double sigma = noise_std(s, params);
  out.noise_std_m = sigma;
  const std::vector<char> steady = steady_samples(s, sigma, params);
  // 6. Plateau means.
  for (const Accumulator& acc : plateau_sums(s, steady, sigma, params, &out.notes)) {
    Plateau p;
    p.start_s = acc.start_s;
    p.end_s = acc.end_s;
    p.deflection_m = acc.mean(s.ref);
    p.deflection_std_m = acc.std();
    p.sample_count = static_cast<int>(acc.count);
    out.plateaus.push_back(p);
  }
  return out;
}

std::string steps_from_plateaus(const std::vector<Plateau>& plateaus,
                                const std::vector<double>& added_masses_kg,
                                std::vector<BallastStep>* steps) {
  steps->clear();
  if (plateaus.size() != added_masses_kg.size()) {
    std::string list;
    for (std::size_t i = 0; i < plateaus.size(); ++i) {
      char buf[128];
      std::snprintf(buf, sizeof buf, "%s%zu) %s: %.3f mm", i == 0 ? "" : ", ", i + 1,
                    span(plateaus[i].start_s, plateaus[i].end_s).c_str(),
                    plateaus[i].deflection_m * 1e3);
      list += buf;
    }
    return "found " + std::to_string(plateaus.size()) + " standstill plateaus but " +
           std::to_string(added_masses_kg.size()) +
           " ballast masses were given (one per plateau, in time order, the empty vehicle "
           "included)" +
           (list.empty() ? std::string() : ": " + list);
  }
  for (std::size_t i = 0; i < plateaus.size(); ++i) {
    BallastStep s;
    s.added_mass_kg = added_masses_kg[i];
    s.deflection_m = plateaus[i].deflection_m;
    s.deflection_std_m = plateaus[i].deflection_std_m;
    s.sample_count = plateaus[i].sample_count;
    s.start_s = plateaus[i].start_s;
    s.end_s = plateaus[i].end_s;
    steps->push_back(s);
  }
  return "";
}

}  // namespace vmass::calibrate
