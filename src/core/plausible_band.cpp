#include "vmass/core/plausible_band.hpp"

#include <cmath>

namespace vmass {
namespace {

constexpr double kLowPerEmpty = 0.9;
constexpr double kHighPerMax = 1.25;
constexpr double kHighPerEmptyWithoutMax = 3.0;

}  // namespace

MassBand plausible_mass_band(const VehicleParams& v) {
  MassBand band;
  band.low_kg = kLowPerEmpty * v.empty_mass_kg;
  band.high_kg = std::isfinite(v.max_mass_kg) ? kHighPerMax * v.max_mass_kg
                                              : kHighPerEmptyWithoutMax * v.empty_mass_kg;
  return band;
}

}  // namespace vmass
