#include "vmass/core/converter_map.hpp"

#include <cmath>

namespace vmass {

double ConverterMap::torque_ratio(double speed_ratio) const {
  if (!known_ || speed_ratio >= coupling_) return 1.0;
  return stall_ - (stall_ - 1.0) * speed_ratio / coupling_;
}

ConverterReading ConverterMap::read(double engine_speed_radps, double turbine_speed_radps) const {
  ConverterReading r;
  if (!(turbine_speed_radps > 0.0) || !(engine_speed_radps > 0.0)) return r;
  r.speed_ratio = turbine_speed_radps / engine_speed_radps;
  const double slip = std::abs(engine_speed_radps - turbine_speed_radps);
  if (slip <= locked_slip_ * turbine_speed_radps) {
    r.coupling = DrivelineCoupling::kLocked;
    return r;
  }
  // Driving through the converter: the engine leads the turbine.
  if (known_ && r.speed_ratio < 1.0 && r.speed_ratio >= kMinSpeedRatio) {
    r.coupling = DrivelineCoupling::kConverter;
    r.torque_ratio = torque_ratio(r.speed_ratio);
  }
  return r;
}

}  // namespace vmass
