// candump's plain screen output (can-utils `candump can0`, what people paste and `cantools
// decode` reads), line by line:
//
//   (1700000000.123456)  can0  123   [8]  11 22 33 44 55 66 77 88     (-t a: absolute time)
//     can0  1F334455   [4]  DE AD BE EF                                 (no time: 0)
//     can0  123  [12]  00 11 22 33 44 55 66 77 88 99 AA BB              (more than 8: CAN FD)
//     can0  123   [2]  remote request
//     can0  20000004   [8]  00 04 00 00 00 00 00 00   ERRORFRAME
//
// Extra columns of -x (RX/TX and FD flags before the id) and the text -a prints after the data
// are skipped. The id is 3 hex digits (11-bit) or 8 (29-bit; bit 0x20000000: an error frame).
// A recording needs times: with `require_time`, a line without one is corrupt.
//
// Thread-safety: one parser per thread.
#pragma once

#include <string>
#include <string_view>

#include "vmass/can/log_line_parser.hpp"

namespace vmass::can {

class CandumpScreenParser final : public LogLineParser {
 public:
  explicit CandumpScreenParser(bool require_time) : require_time_(require_time) {}
  CandumpLine parse(std::string_view line, CandumpRecord* record, std::string* error) override;

 private:
  bool require_time_;
  std::string interface_;
};

/// True when the line looks like candump's screen output ("IFACE ID [LEN] ...").
bool is_candump_screen_line(std::string_view line);

}  // namespace vmass::can
