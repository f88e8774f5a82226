// candump log files (can-utils `candump -l`): a streaming reader and a writer.
//
// A line is `(SECONDS.FRACTION) INTERFACE FRAME [R|T]` with FRAME one of
//   123#DEADBEEF           classic frame, 3 hex digits: 11-bit id
//   12345678#DEADBEEF      8 hex digits: 29-bit id (bit 0x20000000 set: an error frame)
//   123##1DEADBEEF         CAN FD, the digit after ## holds the flags (1 BRS, 2 ESI, 4 FDF)
//   123#R  123#R5          remote request, optionally with its length
// FRACTION has 6 (microseconds) or 9 (nanoseconds, truncated to microseconds) digits. Data may
// use '.' between bytes and a classic frame may end in `_X` (raw DLC 9..F), as can-utils
// accepts. Blank lines and lines starting with '#' or ';' are comments.
//
// The reader never fails on a bad line: it reports the line number and reason, counts it and
// goes on. Lines are bounded (a longer one is corrupt; /dev/zero costs CPU, never memory), and
// a read error ends the input with read_error() set: it is never taken for the end of the file. The
// writer produces exactly what candump -l writes (can-utils 2020.11):
// `(%010ld.%06ld) %s %s\n`, ids as %03X / %08X, data as %02X bytes, FD as ##%X, remote as R.
//
// Thread-safety: one reader or writer per thread; the free functions are reentrant.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

#include "vmass/can/can_frame.hpp"
#include "vmass/io/line_reader.hpp"

namespace vmass::can {

struct CandumpRecord {
  CanFrame frame;
  std::string_view interface;  ///< valid until the next read
  char direction = '\0';       ///< 'R', 'T' or '\0' when absent
};

enum class CandumpLine : std::uint8_t { kFrame, kComment, kCorrupt };

/// Parses one line (without its newline). On kCorrupt, *error (if given) says why.
CandumpLine parse_candump_line(std::string_view line, CandumpRecord* record,
                               std::string* error = nullptr);

/// Formats a frame as candump -l does, including the trailing newline, into buf (allocation
/// free). Returns the number of characters written, or 0 when capacity is too small (200 bytes
/// always suffice for names up to 16 characters).
std::size_t format_candump_line(const CanFrame& frame, std::string_view interface, char* buf,
                                std::size_t capacity);
std::string format_candump_line(const CanFrame& frame, std::string_view interface);

struct CandumpError {
  std::int64_t line = 0;
  std::string message;
};

struct CandumpStats {
  std::uint64_t lines = 0;
  std::uint64_t frames = 0;
  std::uint64_t comments = 0;
  std::uint64_t corrupt = 0;
  std::uint64_t fd_frames = 0;
  std::uint64_t remote_frames = 0;
  std::uint64_t error_frames = 0;
};

class CandumpReader {
 public:
  /// Reads from `in` (kept by reference). `source` names the input in error messages.
  explicit CandumpReader(std::istream& in, std::string source = "log");

  /// Next frame; false at end of input or after a read error (read_error()). Corrupt lines are
  /// counted, reported, skipped.
  bool next(CandumpRecord* record);
  /// "source: read error: why" once the input failed; "" at a clean end.
  const std::string& read_error() const { return read_error_; }

  /// Called for each corrupt line (in addition to keeping the first max_kept_errors).
  void on_error(std::function<void(const CandumpError&)> callback) {
    callback_ = std::move(callback);
  }
  const std::vector<CandumpError>& errors() const { return errors_; }
  const CandumpStats& stats() const { return stats_; }
  const std::string& source() const { return source_; }
  std::int64_t line_number() const { return line_no_; }

  static constexpr std::size_t kMaxKeptErrors = 100;
  /// Longest line read (a candump -l line is at most about 200 bytes).
  static constexpr std::size_t kMaxLineBytes = 4096;

 private:
  void corrupt_line(const std::string& why);

  io::LineReader lines_;
  std::string source_;
  std::string read_error_;
  std::string_view line_;  ///< in lines_'s buffer
  std::string why_;
  std::int64_t line_no_ = 0;
  CandumpStats stats_;
  std::vector<CandumpError> errors_;
  std::function<void(const CandumpError&)> callback_;
};

class CandumpWriter {
 public:
  explicit CandumpWriter(std::ostream& out) : out_(out) {}
  void write(const CanFrame& frame, std::string_view interface);

 private:
  std::ostream& out_;
};

}  // namespace vmass::can
