// EstimateCsvWriter: the estimate stream as CSV (docs/formats.md):
//   time_s,mass_kg,mass_ci_low_kg,mass_ci_high_kg,mu_n,status, then mass_std_kg,reason,
//   longitudinal_pairs,lateral_pairs,longitudinal_availability,lateral_availability,
//   initial_mass_kg
// Before the first estimate (no prior yet) the cells mass_kg, mass_ci_low_kg, mass_ci_high_kg,
// mu_n, mass_std_kg and initial_mass_kg are empty.
// Numbers are written locale-free with fixed precision (time %.2f, masses and mu %.3f,
// availabilities %.5f, as printf writes them: vmass/csv/fixed_decimal.hpp), so files compare
// byte for byte (the golden replay test relies on it). Rows are formatted into a buffer that
// is written out in 64 KiB blocks: write() allocates nothing. Not thread-safe.
#pragma once

#include <cstddef>
#include <cstdio>
#include <memory>
#include <string>

#include "vmass/core/estimate.hpp"

namespace vmass {

class EstimateCsvWriter {
 public:
  /// Room format_row() may need: nine numbers of at most kMaxFixedChars, names and counters.
  static constexpr std::size_t kMaxRowChars = 4096;

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
  /// The row of an estimate, without its newline.
  static std::string row(const Estimate& e);
  /// Writes the row of an estimate (without newline) at out, which has room for kMaxRowChars;
  /// returns its end.
  static char* format_row(const Estimate& e, char* out);

 private:
  void flush_buffer();

  std::FILE* file_ = nullptr;
  bool failed_ = false;
  std::unique_ptr<char[]> buffer_;
  std::size_t used_ = 0;
};

}  // namespace vmass
