// CandumpFrameSource: the frames of a candump -l log (can-utils), stamped with the log's times.
// Corrupt lines are counted as malformed, reported through on_error and skipped; a read error
// ends the log with problem() saying so (never a silent end of file).
//
// Thread-safety: one reading thread.
#pragma once

#include <functional>
#include <istream>
#include <memory>
#include <string>

#include "vmass/can/candump.hpp"
#include "vmass/runtime/frame_source.hpp"

namespace vmass::runtime {

/// A candump -l log (can-utils), frames stamped with the log's times. Corrupt lines are counted
/// as malformed and skipped.
class CandumpFrameSource final : public FrameSource {
 public:
  static std::unique_ptr<CandumpFrameSource> open(const std::string& path, std::string* error);
  /// A log held in memory (e.g. a simulated drive's frames); `name` stands for the path in
  /// messages.
  static std::unique_ptr<CandumpFrameSource> from_text(std::string text, const std::string& name);
  Read read(can::CanFrame* frame, int timeout_ms) override;
  bool recorded() const override { return true; }
  std::string describe() const override { return "replay:" + path_; }
  /// The log's read error ("path: read error: ..."), "" while it reads fine.
  std::string problem() const override { return reader_->read_error(); }
  /// Called for each corrupt line (message "path:line: ..."), which is then skipped.
  void on_error(std::function<void(const can::CandumpError&)> callback) {
    reader_->on_error(std::move(callback));
  }
  const can::CandumpStats& stats() const { return reader_->stats(); }
  std::int64_t malformed() const override {
    return static_cast<std::int64_t>(reader_->stats().corrupt);
  }

 private:
  CandumpFrameSource(std::unique_ptr<std::istream> in, const std::string& path);
  std::string path_;
  std::unique_ptr<std::istream> in_;
  std::unique_ptr<can::CandumpReader> reader_;
};

}  // namespace vmass::runtime
