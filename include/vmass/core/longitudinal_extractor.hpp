// LongitudinalExtractor: longitudinal regression pairs (paper eqs. 4-7, Table II).
//
//   F   = C_wheel / r_wheel - P_brake K_brake                      eqs. (6), (7)
//   M da_x = dF   over a step dt (resistive forces cancel)          eq. (5)
// The wheel torque also accelerates the rotating parts, so the differenced relation holds for
// M + m_rot (m_rot = J / r^2, from config, per gear when known). The pair therefore is
//   y = dF - m_rot da_x,   phi = [da_x, 1]
// so that theta[0] is the vehicle mass M.
//
// Gates (Table II, thresholds from config): |a_y| < max_abs_accel_y_mps2 at both ends,
// |da_x| > min_abs_delta_accel_x_mps2, |dF| > min_abs_delta_force_n; and, beyond the paper,
// speed >= min_speed_mps (the brake force model fails at standstill), no gear change inside
// the window, inputs valid and finite, and samples exactly dt apart.
//
// Signals are low-pass filtered identically before differencing (see LowPassFilter).
// Not thread-safe; allocates only in the constructor.
#pragma once

#include <string>

#include "vmass/core/differencing_history.hpp"
#include "vmass/core/extraction.hpp"
#include "vmass/core/low_pass_filter.hpp"
#include "vmass/core/sample.hpp"
#include "vmass/core/vehicle_params.hpp"

namespace vmass {

struct LongitudinalParams {
  bool enabled = true;
  double max_abs_accel_y_mps2 = 0.2;
  double min_abs_delta_accel_x_mps2 = 0.01;
  double min_abs_delta_force_n = 10.0;
  double min_speed_mps = 1.0;
  double weight = 1.0;

  std::string validate() const;
};

class LongitudinalExtractor {
 public:
  LongitudinalExtractor(const VehicleParams& vehicle, const LongitudinalParams& params,
                        const DifferencingParams& differencing);

  Extraction step(const Sample& sample);
  void reset();

  /// Inputs this block needs.
  static constexpr InputMask kRequired =
      input_bit(Input::kWheelTorque) | input_bit(Input::kBrakePressure) |
      input_bit(Input::kAccelX) | input_bit(Input::kAccelY) | input_bit(Input::kSpeed);

 private:
  struct Record {
    TimeUs time_us;
    double accel_x_mps2;
    double accel_y_mps2;
    double force_n;
    double speed_mps;
    int gear;
    bool gear_valid;
  };

  VehicleParams vehicle_;
  LongitudinalParams params_;
  LowPassFilter accel_x_filter_, accel_y_filter_, force_filter_;
  DifferencingHistory<Record> history_;
};

}  // namespace vmass
