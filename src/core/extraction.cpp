#include "vmass/core/extraction.hpp"

#include <cmath>

#include "vmass/core/param_check.hpp"

namespace vmass {

std::string_view verdict_name(PairVerdict v) {
  switch (v) {
    case PairVerdict::kAccepted:
      return "accepted";
    case PairVerdict::kDisabled:
      return "disabled";
    case PairVerdict::kInputsInvalid:
      return "inputs_invalid";
    case PairVerdict::kWarmingUp:
      return "warming_up";
    case PairVerdict::kTimeGap:
      return "time_gap";
    case PairVerdict::kSpeed:
      return "speed";
    case PairVerdict::kLateralAccel:
      return "lateral_accel";
    case PairVerdict::kLongitudinalAccel:
      return "longitudinal_accel";
    case PairVerdict::kSteering:
      return "steering";
    case PairVerdict::kSmallDeltaAccel:
      return "small_delta_accel";
    case PairVerdict::kSmallDeltaForce:
      return "small_delta_force";
    case PairVerdict::kGearChange:
      return "gear_change";
    case PairVerdict::kNonFinite:
      return "non_finite";
    case PairVerdict::kInnovation:
      return "innovation";
    case PairVerdict::kSettling:
      return "settling";
    case PairVerdict::kNotClean:
      return "not_clean";
    case PairVerdict::kImplausible:
      return "implausible";
    case PairVerdict::kAwaitingLag:
      return "awaiting_lag";
    case PairVerdict::kCount:
      break;
  }
  return "unknown";
}

int DifferencingParams::steps() const {
  const long n = std::lround(differencing_dt_s * tick_rate_hz);
  return n < 1 ? 1 : static_cast<int>(n);
}

std::string DifferencingParams::validate(const std::string& section) const {
  ParamCheck c(section);
  c.in_half_open_range("tick_rate_hz", tick_rate_hz, 0.0, 10000.0);
  c.positive("differencing_dt_s", differencing_dt_s);
  c.non_negative("filter_cutoff_hz", filter_cutoff_hz);
  if (tick_rate_hz > 0.0 && filter_cutoff_hz >= 0.5 * tick_rate_hz) {
    c.fail("filter_cutoff_hz", "must be below half the tick rate");
  }
  if (tick_rate_hz > 0.0 && differencing_dt_s > 0.0) {
    const double ticks = differencing_dt_s * tick_rate_hz;
    if (ticks < 0.999 || std::abs(ticks - std::round(ticks)) > 1e-6) {
      c.fail("differencing_dt_s", "must be a whole number (>= 1) of ticks at tick_rate_hz");
    }
    if (ticks > 1000.0) c.fail("differencing_dt_s", "must be at most 1000 ticks");
  }
  return c.message();
}

}  // namespace vmass
