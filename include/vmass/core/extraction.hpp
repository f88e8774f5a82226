// Extraction: what an event extractor (longitudinal, lateral) says about one tick: a regression
// pair, or why there is none. Also the differencing settings both extractors share.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "vmass/core/regression_pair.hpp"

namespace vmass {

/// Why a tick did or did not yield an accepted pair (one diagnostic record per tick and block).
enum class PairVerdict : std::uint8_t {
  kAccepted = 0,
  kDisabled,           ///< block switched off in config
  kInputsInvalid,      ///< a needed input is stale or invalid
  kWarmingUp,          ///< not yet dt of history
  kTimeGap,            ///< the samples dt apart are not dt apart in time
  kSpeed,              ///< below the block's minimum speed
  kLateralAccel,       ///< |a_y| gate (Table II: too large; Table III: too large)
  kLongitudinalAccel,  ///< |a_x| too large for "v_x constant" (Table III)
  kSteering,           ///< |steering-wheel angle| below the Table III minimum
  kSmallDeltaAccel,    ///< |da| below its gate
  kSmallDeltaForce,    ///< |dF| below its gate (Table II)
  kGearChange,         ///< gear changed inside the differencing window
  kNonFinite,          ///< NaN or infinite values
  kInnovation,         ///< rejected by the supervisor's innovation gate
  kSettling,           ///< clean, but not yet for a whole window and its settle time
  kNotClean,           ///< braking, shifting or too slow inside the window
  kImplausible,        ///< the mass the pair implies lies outside the plausible band
  kAwaitingLag,        ///< kept until the driveline lag is identified (released later)
  kCount
};

std::string_view verdict_name(PairVerdict v);

struct Extraction {
  PairVerdict verdict = PairVerdict::kWarmingUp;
  RegressionPair pair;  ///< meaningful when verdict is kAccepted (a candidate for the supervisor)
  bool has_pair() const { return verdict == PairVerdict::kAccepted; }
};

/// How signals are differenced: the tick rate, the differencing step dt (paper: 0.02 s in
/// simulation, 0.2 s on CAN data) and the optional low-pass applied before differencing.
struct DifferencingParams {
  double tick_rate_hz = 100.0;
  double differencing_dt_s = 0.6;
  double filter_cutoff_hz = 0.7;

  /// dt in ticks (>= 1).
  int steps() const;
  /// Errors name their keys under `section` (the config section these values come from).
  std::string validate(const std::string& section = "estimator") const;
};

}  // namespace vmass
