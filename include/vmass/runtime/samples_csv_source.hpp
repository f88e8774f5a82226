// SamplesCsvSource: a samples.csv file (docs/formats.md) as the daemon's input: each row is one
// record at its time_s, updating every input (an empty cell: invalid). A legitimate offline
// input (simulated drives, signals decoded elsewhere) and the daemon's end-to-end test path.
//
// Its input table is an InputValues (the latest row, per-input times) with sample_at() of
// input_source.hpp: inputs older than timeout_s are stale.
// Rows pass a ClockGuard (reorder window, bounded jumps) before they are records.
// Counters: received = rows read, decoded = good rows, malformed = rows skipped as malformed.
// Reading allocates (CSV parsing); it runs on the reading thread, never the estimator's.
// Thread-safety: as InputSource.
#pragma once

#include <memory>
#include <string>

#include "vmass/csv/samples_csv.hpp"
#include "vmass/runtime/clock_guard.hpp"
#include "vmass/runtime/input_source.hpp"

namespace vmass::runtime {

class SamplesCsvSource final : public InputSource {
 public:
  /// Opens the file; nullptr and *error when it cannot be read or its header is wrong.
  /// Inputs older than timeout_s are stale.
  static std::unique_ptr<SamplesCsvSource> open(const std::string& path, double timeout_s,
                                                std::string* error);

  Read next_record(int timeout_ms) override;
  TimeUs record_time_us() const override { return record_.time_us; }
  void copy_record(InputRecord* record) const override;

  void apply(const InputRecord& record) override;
  Sample sample_at(TimeUs tick_us) override;
  TimeUs input_age_us(Input input, TimeUs tick_us) const override;

  std::string read_error() const override { return reader_.read_error(); }
  bool recorded() const override { return true; }
  std::string describe() const override { return "samples:" + path_; }

  /// The table (estimator thread).
  const InputValues& values() const { return values_; }

  /// Row problems reported by the reader (file:line: ...), at most the first 100.
  const std::vector<std::string>& warnings() const { return reader_.warnings(); }

 private:
  SamplesCsvSource(const std::string& path, double timeout_s);

  std::string path_;
  SamplesCsvReader reader_;
  InputTimeouts timeouts_;
  Sample record_;  ///< reading thread
  ClockGuard<Sample> guard_;
  bool ended_ = false;
  InputValues values_;  ///< estimator thread
};

}  // namespace vmass::runtime
