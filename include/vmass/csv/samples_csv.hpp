// SamplesCsvReader: streams Samples from a samples.csv file (docs/formats.md): the estimator's
// inputs per row, an empty cell meaning "invalid at this tick". Errors name the file and line;
// a malformed row is reported and skipped (counted), never fatal: a time that does not increase
// on the previous row's, |time_s| > 1e10 s, a row longer than 64 KiB. A read error ends the
// input with read_error() set (never taken for the end of the file).
// Not thread-safe.
#pragma once

#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "vmass/core/sample.hpp"
#include "vmass/io/line_reader.hpp"

namespace vmass {

class SamplesCsvReader {
 public:
  /// Opens the file and reads the header; check error() afterwards.
  explicit SamplesCsvReader(const std::string& path);

  /// The next good row, or nullopt at the end of the file.
  std::optional<Sample> next();

  /// Fatal problem (cannot open, bad header); empty when fine.
  const std::string& error() const { return error_; }
  /// Problems with individual rows ("file:line: ..."), at most the first 100.
  const std::vector<std::string>& warnings() const { return warnings_; }
  long skipped_rows() const { return skipped_rows_; }
  /// "path: read error: why" once reading failed; "" at a clean end.
  const std::string& read_error() const { return read_error_; }

  static constexpr std::size_t kMaxLineBytes = 64 * 1024;
  static constexpr double kMaxAbsTimeS = 1e10;  ///< about 317 years: microseconds fit int64

 private:
  void warn(const std::string& message);

  std::string path_;
  std::ifstream in_;
  io::LineReader lines_;
  std::string read_error_;
  long line_ = 0;
  std::vector<int> column_of_input_;  ///< per Input: column index or -1
  int time_column_ = -1;
  std::size_t column_count_ = 0;
  std::string error_;
  std::vector<std::string> warnings_;
  long skipped_rows_ = 0;
  TimeUs last_time_us_ = 0;
  bool has_last_time_ = false;
};

/// The CSV header column for an input (e.g. "accel_x_mps2").
std::string samples_csv_column(Input in);

}  // namespace vmass
