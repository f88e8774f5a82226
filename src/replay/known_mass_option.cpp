#include "vmass/replay/known_mass_option.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "vmass/core/plausible_band.hpp"

namespace vmass {
namespace {

constexpr double kDefaultStdFraction = 0.005;

bool parse_number(const std::string& text, double* out) {
  const auto r = std::from_chars(text.data(), text.data() + text.size(), *out);
  return r.ec == std::errc() && r.ptr == text.data() + text.size() && std::isfinite(*out);
}

std::vector<std::string> split_colons(const std::string& value) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t colon = value.find(':'); colon != std::string::npos;
       colon = value.find(':', start)) {
    parts.push_back(value.substr(start, colon - start));
    start = colon + 1;
  }
  parts.push_back(value.substr(start));
  return parts;
}

}  // namespace

std::string parse_known_masses(const std::vector<std::string>& values, const VehicleParams& vehicle,
                               std::vector<KnownMassEvent>* out) {
  const MassBand band = plausible_mass_band(vehicle);
  for (const std::string& value : values) {
    const std::string where = "--known-mass '" + value + "': ";
    const std::vector<std::string> parts = split_colons(value);
    KnownMassEvent e;
    if (parts.size() < 2 || parts.size() > 3 || !parse_number(parts[0], &e.time_s) ||
        !parse_number(parts[1], &e.mass_kg)) {
      return where + "expected TIME:KG or TIME:KG:STD (seconds since the log's start, kg)";
    }
    e.std_kg = kDefaultStdFraction * e.mass_kg;
    if (parts.size() == 3 && (!parse_number(parts[2], &e.std_kg) || !(e.std_kg > 0.0))) {
      return where + "STD must be a number of kg > 0";
    }
    if (e.time_s < 0.0) return where + "TIME must be >= 0";
    if (!band.contains(e.mass_kg)) {
      return where + "the mass is outside the config's plausible band [" +
             std::to_string(static_cast<long>(band.low_kg)) + ", " +
             std::to_string(static_cast<long>(band.high_kg)) + "] kg";
    }
    out->push_back(e);
  }
  std::stable_sort(out->begin(), out->end(), [](const KnownMassEvent& a, const KnownMassEvent& b) {
    return a.time_s < b.time_s;
  });
  return "";
}

}  // namespace vmass
