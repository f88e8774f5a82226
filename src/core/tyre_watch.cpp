#include "vmass/core/tyre_watch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "vmass/core/param_check.hpp"

namespace vmass {
namespace {

/// |log s| beyond this is no speed signal of this car's wheels (a wrong config, a launch that
/// was no launch): such a launch is not taken, nor a saved state restored.
constexpr double kMaxAbsLogRatio = 0.3;

bool finite(double x) { return std::isfinite(x); }

bool plausible(const LaunchSums& s) {
  return finite(s.count) && finite(s.sum) && finite(s.sum_sq) && s.count >= 0.0 &&
         s.sum_sq >= 0.0 && std::abs(s.sum) <= kMaxAbsLogRatio * s.count;
}

bool plausible(const SpanSums& s) { return plausible(s.kind[0]) && plausible(s.kind[1]); }

std::size_t index(SpanKind kind) { return static_cast<std::size_t>(kind); }

}  // namespace

std::string TyreWatchParams::validate() const {
  ParamCheck c("estimator.learning.tyre_watch");
  c.in_open_range("launch_std", launch_std, 0.0, 0.2);
  c.at_least("min_launches_for_spread", static_cast<double>(min_launches_for_spread), 2.0);
  c.at_least("min_launches_each_side", static_cast<double>(min_launches_each_side), 1.0);
  c.positive("change_sigma", change_sigma);
  c.in_open_range("min_change_fraction", min_change_fraction, 0.0, 0.2);
  c.positive("suspect_sigma", suspect_sigma);
  return c.message();
}

void TyreWatch::add_span(SpanKind kind, double accel_dv_mps, double speed_dv_mps) {
  if (!params_.enabled || !(accel_dv_mps > 0.0) || !(speed_dv_mps > 0.0) || !finite(accel_dv_mps) ||
      !finite(speed_dv_mps)) {
    return;
  }
  const double x = std::log(accel_dv_mps / speed_dv_mps);
  if (std::abs(x) > kMaxAbsLogRatio) return;
  state_.drive.kind[index(kind)].add(x);
  ++revision_;
}

SpanSums TyreWatch::held() const {
  SpanSums all = state_.settled;
  for (long i = 0; i < state_.window_drives; ++i) all.add(state_.window[std::size_t(i)]);
  all.add(state_.drive);
  return all;
}

double TyreWatch::log_ratio(SpanKind kind) const {
  const LaunchSums one = held().kind[index(kind)];
  return one.count > 0.0 ? one.mean() : std::numeric_limits<double>::quiet_NaN();
}

// Pooled over the drives: the scatter of launches about their own drive's mean (a step between
// drives does not widen it). Never below launch_std, which holds what varies from drive to drive
// (the load's pitch and slip, the roads).
double TyreWatch::launch_std() const {
  if (state_.spread_dof + 1.0 < static_cast<double>(params_.min_launches_for_spread)) {
    return params_.launch_std;
  }
  return std::max(params_.launch_std, std::sqrt(state_.spread_sum_sq / state_.spread_dof));
}

// Each series' step across the boundary, weighed by its precision; false when neither series
// has spans on both sides.
bool TyreWatch::series_step(const SpanSums& before, const SpanSums& after, double* step,
                            double* variance) const {
  const double var1 = launch_std() * launch_std();
  double precision = 0.0;
  double weighted = 0.0;
  for (int k = 0; k < kSpanKinds; ++k) {
    const LaunchSums& b = before.kind[std::size_t(k)];
    const LaunchSums& a = after.kind[std::size_t(k)];
    if (b.count < 1.0 || a.count < 1.0) continue;
    const double w = 1.0 / (var1 * (1.0 / a.count + 1.0 / b.count));
    precision += w;
    weighted += w * (a.mean() - b.mean());
  }
  if (!(precision > 0.0)) return false;
  *step = weighted / precision;
  *variance = 1.0 / precision;
  return true;
}

bool TyreWatch::best_step(int* boundary, double* step, double* variance) const {
  const double min_each = static_cast<double>(params_.min_launches_each_side);
  double best = -1.0;
  SpanSums before = state_.settled;
  for (int b = 0; b < state_.window_drives; ++b) {
    if (b > 0) before.add(state_.window[std::size_t(b - 1)]);
    SpanSums after;
    for (long i = b; i < state_.window_drives; ++i) after.add(state_.window[std::size_t(i)]);
    double d = 0.0;
    double v = 0.0;
    if (before.count() < min_each || after.count() < min_each ||
        !series_step(before, after, &d, &v)) {
      continue;
    }
    const double z = std::abs(d) / std::sqrt(v);
    if (z > best) {
      best = z;
      *boundary = b;
      *step = d;
      *variance = v;
    }
  }
  return best >= 0.0;
}

void TyreWatch::restart_after(int boundary) {
  SpanSums after;
  for (long i = boundary; i < state_.window_drives; ++i) after.add(state_.window[std::size_t(i)]);
  state_.settled = after;
  state_.window = {};
  state_.window_drives = 0;
  ++state_.changes;
}

// From the state alone, so that a restored watch suspects what the saved one did.
void TyreWatch::update_suspicion() {
  suspected_variance_ = 0.0;
  standing_ = TyreVerdict{};
  int boundary = 0;
  double step = 0.0;
  double variance = 0.0;
  if (!best_step(&boundary, &step, &variance)) return;
  standing_.log_step = step;
  standing_.log_step_var = variance;
  standing_.best_sigma = std::abs(step) / std::sqrt(variance);
  if (std::abs(step) >= params_.suspect_sigma * std::sqrt(variance) &&
      std::abs(step) > params_.min_change_fraction) {
    suspected_variance_ = step * step;
  }
}

TyreVerdict TyreWatch::end_drive() {
  ++revision_;
  last_ = TyreVerdict{};
  const SpanSums drive = state_.drive;
  state_.drive = SpanSums{};
  for (const LaunchSums& one : drive.kind) {
    if (one.count < 2.0) continue;
    state_.spread_sum_sq += std::max(one.sum_sq - one.sum * one.sum / one.count, 0.0);
    state_.spread_dof += one.count - 1.0;
  }
  if (drive.count() == 0.0) return last_;  // nothing new to tell a step by
  if (state_.window_drives == kTyreWatchWindowDrives) {
    state_.settled.add(state_.window[0]);
    for (int i = 1; i < kTyreWatchWindowDrives; ++i) state_.window[i - 1] = state_.window[i];
    --state_.window_drives;
  }
  state_.window[state_.window_drives++] = drive;
  int boundary = 0;
  double step = 0.0;
  double variance = 0.0;
  if (!best_step(&boundary, &step, &variance)) return last_;
  last_.best_sigma = std::abs(step) / std::sqrt(variance);
  last_.log_step = step;
  last_.log_step_var = variance;
  if (last_.best_sigma > params_.change_sigma && std::abs(step) > params_.min_change_fraction) {
    last_.changed = true;
    restart_after(boundary);
  }
  update_suspicion();
  return last_;
}

// The spans read so far are the old tyres'; their scatter and the changes told stay.
void TyreWatch::tyres_declared() {
  state_.settled = SpanSums{};
  state_.window = {};
  state_.window_drives = 0;
  state_.drive = SpanSums{};
  standing_ = TyreVerdict{};
  suspected_variance_ = 0.0;
  ++revision_;
}

void TyreWatch::reset() {
  state_ = TyreWatchState{};
  last_ = TyreVerdict{};
  standing_ = TyreVerdict{};
  suspected_variance_ = 0.0;
  ++revision_;
}

// The messages name the state file's keys.
std::string TyreWatch::implausible(const TyreWatchState& s) {
  if (!plausible(s.settled)) return "tyre_watch_settled: launch sums out of range";
  if (!plausible(s.drive)) return "tyre_watch_drive: launch sums out of range";
  if (s.window_drives < 0 || s.window_drives > kTyreWatchWindowDrives) {
    return "tyre_watch_window_drives: out of range";
  }
  for (long i = 0; i < kTyreWatchWindowDrives; ++i) {
    if (!plausible(s.window[std::size_t(i)])) {
      return "tyre_watch_window_" + std::to_string(i + 1) + ": launch sums out of range";
    }
  }
  if (!finite(s.spread_sum_sq) || !finite(s.spread_dof) || s.spread_sum_sq < 0.0 ||
      s.spread_dof < 0.0) {
    return "tyre_watch_spread: out of range";
  }
  if (s.changes < 0) return "tyre_watch_changes: out of range";
  return "";
}

bool TyreWatch::restore(const TyreWatchState& state) {
  if (!implausible(state).empty()) return false;
  state_ = state;
  update_suspicion();
  ++revision_;
  return true;
}

}  // namespace vmass
