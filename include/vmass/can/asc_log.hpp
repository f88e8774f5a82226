// Vector ASC logs (CANoe, CANalyzer, python-can's ASCWriter), read line by line.
//
//   date Wed Jan 10 10:55:25.123 am 2024        header: start date
//   base hex  timestamps absolute                 number base of ids and data; absolute times
//                                                 count from the start, relative ones from the
//                                                 previous line
//   Begin Triggerblock Wed Jan 10 10:55:25.123 am 2024    the measurement's start (preferred)
//      0.015991 1  123             Rx   d 8 01 02 03 04 05 06 07 08 [Length = ...]
//      0.016000 1  1ABCDEF0x       Tx   r 8                           (remote, 29-bit id)
//      0.017000 CANFD   1 Rx  123  [name]  1 0 d 12 <12 bytes> ...   (CAN FD: brs esi dlc len)
//      0.018000 1  ErrorFrame                                         (error frame)
//
// A frame's time is the start date (UTC; its fraction is milliseconds, as CANoe writes three
// digits and python-can fewer) plus its offset, so a log whose date is unreadable counts from 0.
// The channel N becomes interface "can<N-1>" (python-can numbers channels from 0). Lines with
// a time but no frame (Start of measurement, Statistic:, Status:, SV:, J1939 ...) are events, not
// errors; a frame line that does not parse is corrupt.
//
// Thread-safety: one parser per thread.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "vmass/can/log_line_parser.hpp"

namespace vmass::can {

class AscParser final : public LogLineParser {
 public:
  CandumpLine parse(std::string_view line, CandumpRecord* record, std::string* error) override;

  /// The start date's time, microseconds since 1970 (UTC); 0 until a date was read.
  std::int64_t start_us() const { return start_us_; }

 private:
  CandumpLine parse_header(std::string_view line, std::string* error);
  CandumpLine parse_timed(std::string_view line, CandumpRecord* record, std::string* error);

  int base_ = 16;
  bool relative_ = false;
  bool have_trigger_date_ = false;
  std::int64_t start_us_ = 0;
  std::int64_t last_offset_us_ = 0;
  std::string interface_;
};

/// The time of an ASC date "Wed Jan 10 10:55:25.123 am 2024" (am/pm optional), microseconds
/// since 1970 read as UTC; false when it is not one.
bool parse_asc_date(std::string_view text, std::int64_t* time_us);

}  // namespace vmass::can
