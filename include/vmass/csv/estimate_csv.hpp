// EstimateCsvWriter: the estimate stream as CSV (docs/formats.md):
//   time_s,mass_kg,mass_ci_low_kg,mass_ci_high_kg,mu_n,status, then mass_std_kg,reason,
//   longitudinal_pairs,lateral_pairs,longitudinal_availability,lateral_availability,
//   initial_mass_kg
// Before the first estimate (no prior yet) the cells mass_kg, mass_ci_low_kg, mass_ci_high_kg,
// mu_n, mass_std_kg and initial_mass_kg are empty.
// Numbers are written locale-free with fixed precision, so files compare byte for byte (the
// golden replay test relies on it). Not thread-safe.
#pragma once

#include <cstdio>
#include <string>

#include "vmass/core/estimate.hpp"

namespace vmass {

class EstimateCsvWriter {
 public:
  /// Opens (truncates) path; check ok().
  explicit EstimateCsvWriter(const std::string& path);
  ~EstimateCsvWriter();
  EstimateCsvWriter(const EstimateCsvWriter&) = delete;
  EstimateCsvWriter& operator=(const EstimateCsvWriter&) = delete;

  bool ok() const { return file_ != nullptr; }
  void write(const Estimate& e);
  /// Flush and close; false when a write failed (disk full...).
  bool close();

  static std::string header();
  static std::string row(const Estimate& e);

 private:
  std::FILE* file_ = nullptr;
  bool failed_ = false;
};

}  // namespace vmass
