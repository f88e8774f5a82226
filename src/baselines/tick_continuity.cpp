#include "vmass/baselines/tick_continuity.hpp"

#include <cstdlib>

namespace vmass::baselines {

TickContinuity::TickContinuity(double tick_rate_hz)
    : period_us_(vmass::from_seconds(1.0 / tick_rate_hz)),
      tolerance_us_(vmass::from_seconds(0.5 / tick_rate_hz)) {}

bool TickContinuity::follows(vmass::TimeUs time_us) {
  const bool ok = has_last_ && std::llabs((time_us - last_us_) - period_us_) <= tolerance_us_;
  last_us_ = time_us;
  has_last_ = true;
  return ok;
}

}  // namespace vmass::baselines
