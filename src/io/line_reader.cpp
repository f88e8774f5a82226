#include "vmass/io/line_reader.hpp"

#include <cerrno>
#include <cstring>
#include <ios>
#include <system_error>

namespace vmass::io {

bool LineReader::next(std::string* line) {
  line->clear();
  overlong_ = false;
  if (!error_.empty()) return false;
  std::streambuf* buf = in_.rdbuf();
  bool any = false;
  try {
    for (;;) {
      errno = 0;
      const int c = buf->sbumpc();
      if (c == std::char_traits<char>::eof()) {
        // libstdc++'s filebuf throws on a read error; other buffers may only set errno.
        if (errno != 0 && errno != EAGAIN) error_ = std::strerror(errno);
        break;
      }
      any = true;
      if (c == '\n') break;
      if (line->size() < max_) {
        line->push_back(static_cast<char>(c));
      } else {
        overlong_ = true;  // the rest of the line is skipped
      }
    }
  } catch (const std::ios_base::failure& e) {
    // libstdc++ carries the read's errno in the code (system or generic category).
    const std::error_code& code = e.code();
    const bool is_errno =
        code.category() == std::system_category() || code.category() == std::generic_category();
    error_ = code.value() > 0 && is_errno ? std::strerror(code.value()) : e.what();
    in_.setstate(std::ios::badbit);
    return false;
  }
  if (!error_.empty() || !any) return false;
  if (!line->empty() && line->back() == '\r') line->pop_back();
  ++line_number_;
  return true;
}

}  // namespace vmass::io
