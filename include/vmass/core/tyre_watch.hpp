// TyreWatch: new tyres told by the car itself, from its launches and stops.
//
// The ESC's speed signal is the wheels' rotation times the radius it assumes, so new tyres (worn
// tread replaced by new: the radius 1-3 % larger) make it read every speed low by their factor
// f. The accelerometer does not see the tyres. Each launch from a standstill, and each stop to
// one (LaunchIntegrator), measures
//   s = (integral of a_x - its standstill reading) / (the speed signal's change)
// The standstill reading holds the grade and the accelerometer's bias, so s is a constant of the
// car (its body pitch, the accelerometer's scale, the speed signal's radius error) until the
// tyres change, and then it steps by exactly f. So does the lumped scale kappa (LearntScale):
// the wheel torque is read as a force through the config's radius, T / r_config = f T / r_new.
// A step of log s therefore both tells that the tyres changed and measures how far the learnt
// scale moved with them.
//
// (A drive's pairs give s too, as da_x against dv', but the driven wheels' slip under a changing
// torque scatters it by 3 % from drive to drive: docs/estimator.md.)
//
// Launches and stops are two series: the driven wheels slip forward under traction and back
// under the brakes, so a stop reads s about 3 % above a launch of the same car (the held-out
// cars). Each series' step is the tyres', so each boundary's step is the two series' steps,
// weighed by their precision. One launch's log s scatters by a few tenths of a per cent about
// its series (the grade changing under it, the slip at its end), and most drives have one or
// two. So the change is found across drives: tyres change while the car
// is parked, and at each drive's end every boundary between the last window_drives drives is
// tried (the launches since it against those before, since the last change); the largest step,
// if beyond change_sigma of its std and min_change_fraction, is a change, and the launches after
// it start the belief again. A step beyond suspect_sigma that is not yet a change is suspected:
// the interval holds it until the launches confirm or clear it.
//
// Pure; allocates nothing; not thread-safe (one owner).
#pragma once

#include <array>
#include <cstdint>
#include <string>

namespace vmass {

struct TyreWatchParams {
  bool enabled = true;
  /// One span's std of log s, and its floor once spans enough (min_launches_for_spread)
  /// measure it: what varies from drive to drive (the load's pitch and slip, the roads) is not in
  /// a drive's own scatter. 1 % read no step beyond 2.0 std in 400 drives on the same tyres.
  double launch_std = 0.007;
  long min_launches_for_spread = 10;
  /// A step is tried with at least this many launches on each side ...
  long min_launches_each_side = 3;
  /// ... and is a change beyond this many of its std ...
  double change_sigma = 4.0;
  /// ... and beyond this fraction (smaller steps move the mass less than its interval).
  double min_change_fraction = 0.006;
  /// A step beyond this many std (and min_change_fraction) but not yet a change is suspected:
  /// until the next drive's end the interval holds it (suspected_variance()).
  double suspect_sigma = 2.5;

  std::string validate() const;
};

/// A launch from a standstill, or a stop to one (each a series of its own).
enum class SpanKind : std::uint8_t { kLaunch = 0, kStop = 1 };
constexpr int kSpanKinds = 2;

/// One series' sums of x = log s.
struct LaunchSums {
  double count = 0.0;
  double sum = 0.0;
  double sum_sq = 0.0;
  void add(double x) {
    count += 1.0;
    sum += x;
    sum_sq += x * x;
  }
  void add(const LaunchSums& o) {
    count += o.count;
    sum += o.sum;
    sum_sq += o.sum_sq;
  }
  double mean() const { return sum / count; }
};

/// Both series' sums.
struct SpanSums {
  std::array<LaunchSums, kSpanKinds> kind{};
  void add(const SpanSums& o) {
    for (int k = 0; k < kSpanKinds; ++k) kind[std::size_t(k)].add(o.kind[std::size_t(k)]);
  }
  double count() const { return kind[0].count + kind[1].count; }
};

/// The drives the change can be found in.
constexpr int kTyreWatchWindowDrives = 16;

/// The persisted part (plain values).
struct TyreWatchState {
  SpanSums settled;  ///< launches and stops since the last change, before the window
  std::array<SpanSums, kTyreWatchWindowDrives> window{};  ///< the last drives', oldest first
  long window_drives = 0;
  SpanSums drive;  ///< this drive's so far
  /// Within-drive scatter: the sum of squares about each drive's mean, and its degrees of freedom.
  double spread_sum_sq = 0.0;
  double spread_dof = 0.0;
  long changes = 0;  ///< tyre changes detected
};

/// What end_drive() found.
struct TyreVerdict {
  bool changed = false;
  /// The largest step tried, of log s (and of log kappa): new - old; a change when `changed`.
  double log_step = 0.0;
  double log_step_var = 0.0;  ///< its variance
  /// The largest step tried (a change or not), in its std: how close the drive came to one.
  double best_sigma = 0.0;
};

class TyreWatch {
 public:
  explicit TyreWatch(const TyreWatchParams& params) : params_(params) {}

  /// One launch or stop: the accelerometer's integrated change of speed and the speed
  /// signal's, m/s (both positive).
  void add_span(SpanKind kind, double accel_dv_mps, double speed_dv_mps);
  /// The drive ends (a power cycle): its launches join the window, and a step is looked for.
  TyreVerdict end_drive();
  /// New tyres declared: the change is known, so the launches start again from it.
  void tyres_declared();
  /// Forget everything (a user's reset of what was learnt).
  void reset();

  /// The launches and stops since the last change (this drive's included).
  SpanSums held() const;
  /// One series' log s since the last change (NaN without any), and one span's std.
  double log_ratio(SpanKind kind) const;
  double launch_std() const;
  const TyreWatchState& state() const { return state_; }
  /// What the last end_drive() found.
  const TyreVerdict& last_verdict() const { return last_; }
  /// The largest step the window holds now (after the last end_drive() or restore(); never
  /// `changed`): what a status shows between drives' ends.
  const TyreVerdict& standing() const { return standing_; }
  /// Counts every change of what the watch holds (a status republishes only then).
  long revision() const { return revision_; }
  /// The square of a suspected step (0 when none): what the learnt scale may have moved by.
  double suspected_variance() const { return suspected_variance_; }
  bool restore(const TyreWatchState& state);
  /// "" when the state is one restore() takes, else why not.
  static std::string implausible(const TyreWatchState& state);

 private:
  /// The best boundary in the window: its index (1..window_drives-1 or window_drives for "this
  /// drive alone"), its step and variance; false when no side has launches enough.
  bool best_step(int* boundary, double* step, double* variance) const;
  bool series_step(const SpanSums& before, const SpanSums& after, double* step,
                   double* variance) const;
  void restart_after(int boundary);
  void update_suspicion();

  TyreWatchParams params_;
  TyreWatchState state_;
  TyreVerdict last_;
  TyreVerdict standing_;
  double suspected_variance_ = 0.0;
  long revision_ = 0;
};

}  // namespace vmass
