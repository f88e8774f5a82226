// Reading a truth.csv (docs/formats.md: time_s, mass_kg, then any other columns) into a Truth.
// Thread-safe (a pure function of the file).
#pragma once

#include <optional>
#include <string>

#include "vmass/scoring/truth.hpp"

namespace vmass::scoring {

/// The truth in `path` (a regular file, rows in increasing time, at least one); empty, and why
/// in *error, when it cannot be read.
std::optional<Truth> load_truth_csv(const std::string& path, std::string* error);

}  // namespace vmass::scoring
