// LogFrameSource: the frames of a recorded CAN log in any format vmass reads, the format found
// from the file's content (vmass/can/log_format.hpp):
//
//   candump -l, candump screen output,   read natively, line by line (TextLogFrameSource)
//   Vector ASC, PEAK TRC
//   Vector BLF                           read natively, object by object, with zlib
//                                        (BlfLogFrameSource)
//   ASAM MDF4 bus logging                through vmass-log-convert, which reads it with
//                                        asammdf and hands candump -l lines over a pipe
//                                        (ConvertedLogFrameSource)
//
// Every format reports the way the candump reader does: a line (record) that cannot be read
// is counted in stats().corrupt, reported through on_error as "path:line N: why" (binary:
// "path:record N: why") and skipped; a log is never refused for its content, only when it
// cannot be opened (a directory or a device is refused, vmass/io/regular_file.hpp) or its
// format is not one of these. Text lines are bounded and a read error is problem(), never the
// end of the log (TextLogFrameSource); on a pipe the format is found from the first line.
//
// select_interface("can1") reads one interface of a multi-interface log, in every format
// (interface_selection.hpp): read() skips the frames of the others and counts them, never as
// corrupt; stats() counts the frames read, on the selected interface.
//
// Thread-safety: one reading thread.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "vmass/can/candump.hpp"
#include "vmass/can/log_format.hpp"
#include "vmass/runtime/frame_source.hpp"
#include "vmass/runtime/interface_selection.hpp"

namespace vmass::runtime {

class LogFrameSource : public FrameSource {
 public:
  /// The next frame of the selected interface (of any without a selection).
  Read read(can::CanFrame* frame, int timeout_ms) final;
  bool recorded() const override { return true; }
  std::string describe() const override { return "replay:" + path_; }
  std::string problem() const override { return problem_; }
  std::int64_t malformed() const override { return static_cast<std::int64_t>(stats_.corrupt); }

  can::LogFormat format() const { return format_; }
  const std::string& path() const { return path_; }
  /// Called for each line (record) that is skipped, with "path:N: why".
  void on_error(std::function<void(const can::CandumpError&)> callback) {
    callback_ = std::move(callback);
  }
  /// Lines (records), frames, comments (lines without a frame), corrupt ones, by kind.
  const can::CandumpStats& stats() const { return stats_; }
  /// The line (text) or record (binary) number of the last frame read.
  std::int64_t position() const { return position_; }
  /// "line" for the text formats, "record" for the binary ones.
  std::string_view unit() const { return can::is_binary_format(format_) ? "record" : "line"; }
  /// The interface (channel) of the last frame read, e.g. "can0".
  virtual std::string_view interface_name() const = 0;
  /// From now on read() gives the frames of interface `name` alone
  /// (InterfaceSelection::name_error(name) must be "").
  void select_interface(std::string name) { selection_.emplace(std::move(name)); }
  /// The selection (its name, the frames of other interfaces skipped); null without one.
  const InterfaceSelection* interface_selection() const {
    return selection_ ? &*selection_ : nullptr;
  }
  /// The first line (record) skipped as corrupt: its number and why (line 0 when none was).
  const can::CandumpError& first_corrupt() const { return first_corrupt_; }
  /// "" when the log gave a frame, or skipped no line and selected no interface; else why it
  /// gave none, for a message: "path: no frames: 3 of 3 lines could not be read; the first,
  /// line 1: why", or with a selection "path: no frame on interface can2; the log has can0
  /// (12034 frames), can1 (8800 frames)" (InterfaceSelection::none_taken_reason()).
  std::string no_frames_reason() const;

 protected:
  LogFrameSource(std::string path, can::LogFormat format)
      : path_(std::move(path)), format_(format) {}
  /// The log's next frame on any interface (interface_name() names it) and its line (record)
  /// number; kEnd at the end of the log or after a read error (problem()).
  virtual Read next_frame(can::CanFrame* frame, std::int64_t* position) = 0;
  /// Counts and reports a corrupt line (record) at position.
  void report_corrupt(std::int64_t position, const std::string& why);
  can::CandumpStats& mutable_stats() { return stats_; }
  void set_problem(std::string problem) { problem_ = std::move(problem); }

 private:
  /// Counts a frame read at position (its kind into stats()).
  void count_frame(const can::CanFrame& frame, std::int64_t position);

  std::string path_;
  can::LogFormat format_;
  can::CandumpStats stats_;
  std::int64_t position_ = 0;
  std::string problem_;
  can::CandumpError first_corrupt_;  ///< message: the reason alone
  std::function<void(const can::CandumpError&)> callback_;
  std::optional<InterfaceSelection> selection_;
};

/// Opens a CAN log, its format found from its content. `require_time`: candump screen lines
/// without a time are corrupt (a recording needs times; `vmass-can decode` does not). Null, and
/// *error "path: why", when the file cannot be opened or is not a CAN log vmass reads.
std::unique_ptr<LogFrameSource> open_log_frame_source(const std::string& path, std::string* error,
                                                      bool require_time = true);

}  // namespace vmass::runtime
