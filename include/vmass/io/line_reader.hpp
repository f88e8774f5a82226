// LineReader: lines of a text stream with a bound on their length, and read errors told apart
// from the end of the input.
//
//   next(&line)   the next line without its '\n' (and without a trailing '\r'); false at the end
//                 of the input or after a read error (error() says which). A string_view line
//                 views the reader's buffer, valid until the next call (no copy, no allocation).
//   A line longer than max_line_bytes is cut there: next() returns its first max_line_bytes
//   bytes with overlong() true, and skips the rest of it (so /dev/zero costs CPU, never memory).
//
// std::getline would grow a line without bound, and a read error (EIO, EISDIR) ends it like the
// end of the file: the two faults this reader exists for.
//
// The reader takes from the stream's buffer in blocks (never more than the stream holds
// already, so a line from a live pipe is returned as soon as it is complete) and finds the
// newlines with memchr: a byte-at-a-time reader cost more than the parsing of the line. Bytes
// past the last line returned stay in the reader, so one reader must read the stream to its end.
//
// Not thread-safe; the stream is kept by reference.
#pragma once

#include <cstddef>
#include <cstdint>
#include <istream>
#include <string>
#include <string_view>
#include <vector>

namespace vmass::io {

class LineReader {
 public:
  explicit LineReader(std::istream& in, std::size_t max_line_bytes = 64 * 1024);

  /// See the header comment.
  bool next(std::string_view* line);
  bool next(std::string* line);
  /// The last line returned was cut at max_line_bytes.
  bool overlong() const { return overlong_; }
  /// "" at the end of the input; the system's reason after a read error.
  const std::string& error() const { return error_; }
  /// Lines returned so far (the number of the last one).
  std::int64_t line_number() const { return line_number_; }

 private:
  bool fill();
  bool cut_overlong(std::string_view* line);
  bool give(std::string_view text, std::string_view* line);

  std::istream* in_;
  std::size_t max_;
  std::vector<char> block_;  ///< read from the stream; [begin_, end_) not yet returned
  std::size_t begin_ = 0;
  std::size_t end_ = 0;
  std::string cut_;  ///< an overlong line's first max_ bytes
  bool overlong_ = false;
  std::string error_;
  std::int64_t line_number_ = 0;
};

}  // namespace vmass::io
