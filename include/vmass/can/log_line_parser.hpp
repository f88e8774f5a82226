// LogLineParser: one line-oriented CAN log format (candump -l, candump's screen output, Vector
// ASC, PEAK TRC) turned into frames one line at a time. A parser may keep state from header
// lines (ASC's number base and start date, TRC's version, columns and start time), so one
// parser reads one file, in order.
//
// Every parser sorts a line the way the candump reader does (CandumpLine): a frame, a line that
// carries none (header, comment, event, blank), or a corrupt line with the reason in *error.
// Times are microseconds (CanFrame::time_us), absolute when the file says when it started.
//
// Thread-safety: one parser per thread.
#pragma once

#include <memory>
#include <string>
#include <string_view>

#include "vmass/can/candump.hpp"
#include "vmass/can/log_format.hpp"

namespace vmass::can {

class LogLineParser {
 public:
  virtual ~LogLineParser() = default;
  /// Parses one line (without its newline) into *record (its interface stays valid until the
  /// next call). On kCorrupt, *error says why.
  virtual CandumpLine parse(std::string_view line, CandumpRecord* record, std::string* error) = 0;
};

/// candump -l lines (parse_candump_line).
class CandumpLineParser final : public LogLineParser {
 public:
  CandumpLine parse(std::string_view line, CandumpRecord* record, std::string* error) override {
    return parse_candump_line(line, record, error);
  }
};

/// The parser of a text format; null for binary and unknown formats. `require_time`: candump's
/// screen output without times gives corrupt lines (a recording needs times); otherwise time 0.
std::unique_ptr<LogLineParser> make_log_line_parser(LogFormat format, bool require_time);

}  // namespace vmass::can
