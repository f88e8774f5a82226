// WithinTracker: from when an estimate stays within each of three tolerances of the truth to the
// end. It keeps, per tolerance, the last time the error was outside it: from then on the
// estimate stayed within. Each scorer turns that into its own "time within" (measured from the
// first tick or from the drive's start: replay_summary.hpp, accuracy_metrics.hpp), with errors
// in its own unit (a fraction, or percent). Not thread-safe; allocates nothing.
#pragma once

#include <array>
#include <cstddef>
#include <optional>

#include "vmass/core/time.hpp"

namespace vmass::scoring {

constexpr std::size_t kToleranceCount = 3;
using Tolerances = std::array<double, kToleranceCount>;

class WithinTracker {
 public:
  /// Tolerances in the unit of the errors add() is given.
  explicit WithinTracker(const Tolerances& tolerances) : tolerances_(tolerances) {}

  /// The error's magnitude at t, in increasing time. NaN (no estimate) is outside every
  /// tolerance.
  void add(TimeUs t, double error_magnitude);
  /// The last time the error was outside tolerance i; empty when it never was.
  std::optional<TimeUs> last_outside_us(std::size_t i) const { return last_outside_us_[i]; }

 private:
  Tolerances tolerances_;
  std::array<std::optional<TimeUs>, kToleranceCount> last_outside_us_{};
};

}  // namespace vmass::scoring
