// LogFormat: which kind of CAN log a file is, found from its content (never its name):
//
//   candump -l          "(1700000000.123456) can0 123#DEADBEEF"           (can-utils)
//   candump screen      "  can0  123   [4]  DE AD BE EF", optionally "(seconds) " first
//   Vector ASC          "date ...", "base hex  timestamps absolute", "Begin Triggerblock"
//   PEAK TRC            ";$FILEVERSION=2.1" or ";##..." headers, "1)  12.3  Rx  0123 8 ..."
//   Vector BLF          binary, starts with "LOGG" (read natively: vmass/runtime/blf_reader.hpp)
//   ASAM MDF4           binary, starts with "MDF     " (or "UnFinMF " while being written)
//
// An LCM log (lcm-logger) and MDF 3 are recognised to say what they are. Pure functions.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace vmass::can {

enum class LogFormat : std::uint8_t {
  kUnknown,
  kCandump,        ///< candump -l
  kCandumpScreen,  ///< candump's plain screen output
  kAsc,            ///< Vector ASC
  kTrc,            ///< PEAK TRC (versions 1.0 to 2.1)
  kBlf,            ///< Vector BLF (binary)
  kMdf4,           ///< ASAM MDF4 bus logging (binary)
  kLcmLog,         ///< an LCM log: not CAN frames
  kMdf3,           ///< MDF 3: no bus logging
};

/// How many leading bytes of a file detect_log_format() wants to see.
constexpr std::size_t kLogFormatProbeBytes = 8192;

/// The format of a file whose first bytes are `head` (up to kLogFormatProbeBytes).
LogFormat detect_log_format(std::string_view head);

/// "candump -l", "Vector ASC", ...
std::string_view log_format_name(LogFormat format);

/// True for the binary formats, whose unit is the record (an object, a frame), not the line.
constexpr bool is_binary_format(LogFormat f) {
  return f == LogFormat::kBlf || f == LogFormat::kMdf4;
}

/// True for the format read through the converter (vmass-log-convert, asammdf): MDF4. BLF is
/// read natively (vmass/runtime/blf_reader.hpp).
constexpr bool is_converted_format(LogFormat f) { return f == LogFormat::kMdf4; }

}  // namespace vmass::can
