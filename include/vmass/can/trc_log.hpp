// PEAK TRC logs (PCAN-View, PCAN-Explorer, python-can's TRCWriter), versions 1.0 to 2.1, read
// line by line. Headers are ';' lines: ;$FILEVERSION=2.1, ;$STARTTIME=<days since 1899-12-30,
// UTC>, ;$COLUMNS=N,O,T,B,I,d,R,L,D (2.x: which column is which). Without a version the file is
// 1.0. Frame lines, times in milliseconds from the start:
//
//   1.0     1)      1841 0001 8 00 00 00 00 00 00 00 00
//   1.1     1)      1841.0  Rx         0001  8  00 00 00 00 00 00 00 00
//   1.3     1)      1841.0 1  Rx         0001 -  8  00 00 00 00 00 00 00 00
//   2.x           1       0.000 DT  1      0123 Rx -  8    01 02 03 04 05 06 07 08
//
// An id of more than 4 hex digits is a 29-bit id; "RTR" instead of data (1.x) or type RR (2.x)
// is a remote frame; types FD, FB (BRS), FE (ESI), BI are CAN FD; Error (1.1) and ER (2.x) are
// error frames; other rows (Warng, ST status, EC error counters, EV events) carry no frame.
// A frame's time is $STARTTIME plus its offset (0 plus the offset without one). The bus column
// N becomes interface "can<N-1>".
//
// Thread-safety: one parser per thread.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "vmass/can/log_line_parser.hpp"

namespace vmass::can {

class TrcParser final : public LogLineParser {
 public:
  CandumpLine parse(std::string_view line, CandumpRecord* record, std::string* error) override;

  /// The version read from ;$FILEVERSION, times 10 (10 = 1.0 when absent, 21 = 2.1).
  int version_x10() const { return version_x10_; }

 private:
  CandumpLine parse_header(std::string_view line, std::string* error);
  CandumpLine parse_v1(std::string_view line, CanFrame* f, std::uint32_t* bus, std::string* error);
  CandumpLine parse_v2(std::string_view line, CanFrame* f, std::uint32_t* bus, std::string* error);

  int version_x10_ = 10;
  std::int64_t start_us_ = 0;
  /// Column index of N O T B I d R L l D in a 2.x file (-1: absent).
  std::array<int, 10> column_{};
  bool have_columns_ = false;
  std::string interface_;
};

}  // namespace vmass::can
