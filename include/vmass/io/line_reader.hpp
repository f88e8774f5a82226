// LineReader: lines of a text stream with a bound on their length, and read errors told apart
// from the end of the input.
//
//   next(&line)   the next line without its '\n' (and without a trailing '\r'); false at the end
//                 of the input or after a read error (error() says which)
//   A line longer than max_line_bytes is cut there: next() returns its first max_line_bytes
//   bytes with overlong() true, and skips the rest of it (so /dev/zero costs CPU, never memory).
//
// std::getline would grow a line without bound, and a read error (EIO, EISDIR) ends it like the
// end of the file: the two faults this reader exists for.
//
// Not thread-safe; the stream is kept by reference.
#pragma once

#include <cstddef>
#include <cstdint>
#include <istream>
#include <string>

namespace vmass::io {

class LineReader {
 public:
  explicit LineReader(std::istream& in, std::size_t max_line_bytes = 64 * 1024)
      : in_(in), max_(max_line_bytes) {}

  /// See the header comment.
  bool next(std::string* line);
  /// The last line returned was cut at max_line_bytes.
  bool overlong() const { return overlong_; }
  /// "" at the end of the input; the system's reason after a read error.
  const std::string& error() const { return error_; }
  /// Lines returned so far (the number of the last one).
  std::int64_t line_number() const { return line_number_; }

 private:
  std::istream& in_;
  std::size_t max_;
  bool overlong_ = false;
  std::string error_;
  std::int64_t line_number_ = 0;
};

}  // namespace vmass::io
