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

// NOLINTNEXTLINE(readability-function-size): not split yet (issue 9)
PlateauDetection detect_plateaus(const std::vector<DeflectionPoint>& series,
                                 const PlateauParams& params) {
  PlateauDetection out;
  if (std::string m = params.validate(); !m.empty()) {
    out.error = m;
    return out;
  }
  const std::size_t n = series.size();
  if (n < 3) {
    out.error = "the deflection series has " + std::to_string(n) + " samples; too few";
    return out;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const DeflectionPoint& p = series[i];
    if (!std::isfinite(p.time_s) || !std::isfinite(p.deflection_m)) {
      out.error = "sample " + std::to_string(i) + ": time or deflection is NaN or infinite";
      return out;
    }
    if (i > 0 && !(p.time_s > series[i - 1].time_s)) {
      out.error = "sample " + std::to_string(i) + ": time " + std::to_string(p.time_s) +
                  " s does not increase (previous " + std::to_string(series[i - 1].time_s) + " s)";
      return out;
    }
  }

  // Standing flags, time gaps, sample period.
  std::vector<char> standing(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double v = series[i].speed_mps;
    standing[i] = std::isnan(v) || std::abs(v) <= params.standstill_speed_mps;
  }
  std::vector<double> dts;
  dts.reserve(n - 1);
  for (std::size_t i = 1; i < n; ++i) dts.push_back(series[i].time_s - series[i - 1].time_s);
  const double dt_s = median(dts);
  const double gap_s = std::max(5.0 * dt_s, 0.0);

  // 1. Noise from first differences of standing samples.
  std::vector<double> diffs;
  diffs.reserve(n - 1);
  for (std::size_t i = 1; i < n; ++i) {
    if (standing[i] && standing[i - 1]) {
      diffs.push_back(std::abs(series[i].deflection_m - series[i - 1].deflection_m));
    }
  }
  const double sigma = std::max(params.min_noise_m, 1.4826 * median(diffs) / std::sqrt(2.0));
  out.noise_std_m = sigma;

  // Prefix sums (relative to the first sample for accuracy), moving-sample and gap counts.
  const double ref = series[0].deflection_m;
  std::vector<double> s1(n + 1, 0.0), s2(n + 1, 0.0);
  std::vector<long> moving(n + 1, 0), gaps(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const double z = series[i].deflection_m - ref;
    s1[i + 1] = s1[i] + z;
    s2[i + 1] = s2[i] + z * z;
    moving[i + 1] = moving[i] + (standing[i] ? 0 : 1);
    gaps[i + 1] = gaps[i] + ((i > 0 && series[i].time_s - series[i - 1].time_s > gap_s) ? 1 : 0);
  }
  auto window_mean = [&](std::size_t lo, std::size_t hi) {  // inclusive
    return (s1[hi + 1] - s1[lo]) / static_cast<double>(hi - lo + 1);
  };

  // 2. Steady samples.
  const double half = 0.5 * params.window_s;
  const double t_first = series.front().time_s;
  const double t_last = series.back().time_s;
  std::vector<char> steady(n, 0);
  std::size_t lo = 0, hi = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = series[i].time_s;
    if (t - half < t_first || t + half > t_last) continue;
    while (series[lo].time_s < t - half) ++lo;
    if (hi < i) hi = i;
    while (hi + 1 < n && series[hi + 1].time_s <= t + half) ++hi;
    if (hi - lo + 1 < 3) continue;
    if (moving[hi + 1] - moving[lo] > 0) continue;
    if (gaps[hi + 1] - gaps[lo + 1] > 0) continue;  // a gap between two window samples
    const double count = static_cast<double>(hi - lo + 1);
    const double sum = s1[hi + 1] - s1[lo];
    const double var = std::max(0.0, (s2[hi + 1] - s2[lo] - sum * sum / count) / (count - 1.0));
    // No drift: the means of the window's two halves agree within steady_drift_sigma of
    // their difference's std, 2 sigma / sqrt(count) (a slow ramp passes the std test alone).
    const std::size_t mid = lo + (hi - lo) / 2;
    const double drift = window_mean(mid + 1, hi) - window_mean(lo, mid);
    steady[i] = std::sqrt(var) <= params.steady_std_factor * sigma &&
                std::abs(drift) <= params.steady_drift_sigma * 2.0 * sigma / std::sqrt(count);
  }

  // 3.-5. Runs, trimmed of their settling transient.
  const std::size_t window_n =
      std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(params.window_s / dt_s)));
  const double level_tolerance = 3.0 * sigma / std::sqrt(static_cast<double>(window_n));
  std::vector<Accumulator> kept;
  std::size_t i = 0;
  while (i < n) {
    if (!steady[i]) {
      ++i;
      continue;
    }
    std::size_t b = i;
    while (b + 1 < n && steady[b + 1] && series[b + 1].time_s - series[b].time_s <= gap_s) ++b;
    const std::size_t a = i;
    i = b + 1;

    std::size_t k = a;
    while (k <= b && series[k].time_s < series[a].time_s + params.settle_s) ++k;
    if (k > b) continue;  // shorter than the settling time (typically inside a ramp)
    std::vector<double> second_half;
    for (std::size_t j = k + (b - k) / 2; j <= b; ++j)
      second_half.push_back(series[j].deflection_m);
    const double level = median(second_half) - ref;
    while (k <= b) {
      const std::size_t end = std::min(b, k + window_n - 1);
      if (std::abs(window_mean(k, end) - level) <= level_tolerance) break;
      ++k;
    }
    if (k > b || series[b].time_s - series[k].time_s < params.min_plateau_s) {
      out.notes.push_back("steady run " + span(series[a].time_s, series[b].time_s) +
                          " shorter than plateau.min_plateau_s after settling; ignored");
      continue;
    }
    Accumulator acc;
    acc.start_s = series[k].time_s;
    acc.end_s = series[b].time_s;
    for (std::size_t j = k; j <= b; ++j) {
      const double z = series[j].deflection_m - ref;
      acc.sum += z;
      acc.sum_sq += z * z;
      ++acc.count;
    }
    if (!kept.empty() && std::abs(kept.back().mean(ref) - acc.mean(ref)) < params.min_step_m) {
      Accumulator& prev = kept.back();
      out.notes.push_back("plateaus " + span(prev.start_s, prev.end_s) + " and " +
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

  // 6. Plateau means.
  for (const Accumulator& acc : kept) {
    Plateau p;
    p.start_s = acc.start_s;
    p.end_s = acc.end_s;
    p.deflection_m = acc.mean(ref);
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
