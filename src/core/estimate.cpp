#include "vmass/core/estimate.hpp"

#include <cmath>

namespace vmass {

std::string_view status_name(EstimateStatus s) {
  switch (s) {
    case EstimateStatus::kInitialising:
      return "initialising";
    case EstimateStatus::kStaticOnly:
      return "static_only";
    case EstimateStatus::kConverging:
      return "converging";
    case EstimateStatus::kConverged:
      return "converged";
    case EstimateStatus::kDegraded:
      return "degraded";
  }
  return "unknown";
}

std::string_view reason_name(StatusReason r) {
  switch (r) {
    case StatusReason::kWaitingForStandstill:
      return "waiting_for_standstill";
    case StatusReason::kStaticInitialised:
      return "static_initialised";
    case StatusReason::kLoadChanged:
      return "load_changed";
    case StatusReason::kNoStaticPrior:
      return "no_static_prior";
    case StatusReason::kRefining:
      return "refining";
    case StatusReason::kIntervalNarrow:
      return "interval_narrow";
    case StatusReason::kInputsInvalid:
      return "inputs_invalid";
    case StatusReason::kRestored:
      return "restored";
    case StatusReason::kNoLoadSensor:
      return "no_load_sensor";
    case StatusReason::kLoadChangeSuspected:
      return "load_change_suspected";
    case StatusReason::kLagProvisional:
      return "lag_provisional";
    case StatusReason::kLoadUnchecked:
      return "load_unchecked";
    case StatusReason::kMassImplausible:
      return "mass_implausible";
    case StatusReason::kKnownMass:
      return "known_mass";
    case StatusReason::kModelLimited:
      return "model_limited";
  }
  return "unknown";
}

std::string Estimate::describe_reason() const {
  std::string text(reason_name(reason));
  if (reason == StatusReason::kInputsInvalid) {
    text += ":";
    const char* sep = " ";
    for (int i = 0; i < kInputCount; ++i) {
      if (invalid_inputs & input_bit(static_cast<Input>(i))) {
        text += sep;
        text += input_name(static_cast<Input>(i));
        sep = ", ";
      }
    }
  }
  if (reason == StatusReason::kLoadChangeSuspected) {
    text +=
        ": the pairs since the last stop disagree with the belief (the mass is theirs, the "
        "interval spans both)";
  }
  if (reason == StatusReason::kLagProvisional) {
    text +=
        ": the driveline lag is not identified yet; the pairs held until it is enter at the best "
        "fit so far, the interval includes the lag's uncertainty";
  }
  if (reason == StatusReason::kLoadUnchecked) {
    text +=
        ": restored after the vehicle was off, when the load may have changed; the mass "
        "starts afresh at the first standstill (or with the drive)";
  }
  if (reason == StatusReason::kMassImplausible) {
    text += ": " + describe_rejection() +
            "; nothing is published until an estimate is in the band (check the config's "
            "empty mass and suspension calibration)";
  }
  if (reason == StatusReason::kModelLimited) {
    text +=
        ": more driving will not narrow the interval; what the config leaves unknown about the "
        "car (the torque scale, the rolling radius, the rotating masses) is most of its width, "
        "and a known mass (vmass-ctl known-mass) teaches it";
  }
  if (reason == StatusReason::kKnownMass) {
    text +=
        ": the mass the user declared for this load, published until the load changes; the "
        "drive on it is evidence of the learnt scale";
  }
  return text;
}

std::string Estimate::describe_rejection() const {
  if (plausible) return "";
  const auto kg = [](double v) { return std::to_string(static_cast<long long>(std::lround(v))); };
  if (implausible_mass_kg < plausible_low_kg) {
    return kg(implausible_mass_kg) + " kg below the plausible band (from " + kg(plausible_low_kg) +
           " kg)";
  }
  return kg(implausible_mass_kg) + " kg above the plausible band (up to " + kg(plausible_high_kg) +
         " kg)";
}

}  // namespace vmass
