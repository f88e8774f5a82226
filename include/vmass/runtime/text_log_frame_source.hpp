// TextLogFrameSource: the frames of a line-oriented CAN log (candump -l, candump's screen
// output, Vector ASC, PEAK TRC), each line through the format's can::LogLineParser. Corrupt
// lines are counted, reported ("path:line: why") and skipped, as the candump reader does.
// Lines are bounded as the candump reader's (a longer one is corrupt; /dev/zero costs CPU, never
// memory), and a read error ends the log with problem() "path: read error: why", never taken
// for the end of the file.
//
// Thread-safety: one reading thread.
#pragma once

#include <istream>
#include <memory>
#include <string>
#include <string_view>

#include "vmass/can/log_line_parser.hpp"
#include "vmass/io/line_reader.hpp"
#include "vmass/runtime/log_frame_source.hpp"

namespace vmass::runtime {

class TextLogFrameSource final : public LogFrameSource {
 public:
  TextLogFrameSource(std::unique_ptr<std::istream> in, const std::string& path,
                     can::LogFormat format, std::unique_ptr<can::LogLineParser> parser);
  std::string_view interface_name() const override { return interface_; }

  /// A stream whose format is found from its first line (standard input or a FIFO: nothing can
  /// be read ahead of a live pipe without waiting). Null, and *error, when that line is no CAN
  /// log's.
  static std::unique_ptr<TextLogFrameSource> from_stream(std::unique_ptr<std::istream> in,
                                                         const std::string& name, bool require_time,
                                                         std::string* error);

 protected:
  Read next_frame(can::CanFrame* frame, std::int64_t* position) override;

 private:
  /// `lines` reads *in (from_stream() hands over the reader that read the first line: it may
  /// hold the lines after it).
  TextLogFrameSource(std::unique_ptr<std::istream> in, io::LineReader lines,
                     const std::string& path, can::LogFormat format,
                     std::unique_ptr<can::LogLineParser> parser);
  bool next_line();
  void set_read_error(const std::string& why);

  std::unique_ptr<std::istream> in_;
  io::LineReader lines_;
  bool have_line_ = false;  ///< line_ views first_line_, read ahead by from_stream()
  bool overlong_ = false;   ///< line_ was cut at can::CandumpReader::kMaxLineBytes
  std::unique_ptr<can::LogLineParser> parser_;
  std::string first_line_;
  std::string_view line_;  ///< the current line, in lines_'s buffer or first_line_
  std::string why_, interface_;
  std::int64_t line_no_ = 0;
};

}  // namespace vmass::runtime
