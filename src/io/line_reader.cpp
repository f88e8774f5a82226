#include "vmass/io/line_reader.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <ios>
#include <system_error>

#include "vmass/io/stream_failure.hpp"

namespace vmass::io {
namespace {

/// Bytes taken from the stream at most at once, beside the longest line kept.
constexpr std::size_t kBlockBytes = 64 * 1024;

}  // namespace

LineReader::LineReader(std::istream& in, std::size_t max_line_bytes)
    : in_(&in), max_(max_line_bytes), block_(max_line_bytes + kBlockBytes) {}

bool LineReader::next(std::string* line) {
  std::string_view view;
  const bool got = next(&view);
  line->assign(view.data(), view.size());
  return got;
}

bool LineReader::next(std::string_view* line) {
  *line = {};
  overlong_ = false;
  if (!error_.empty()) return false;
  std::size_t scanned = 0;  // bytes after begin_ known to hold no '\n'
  for (;;) {
    const char* from = block_.data() + begin_;
    const auto* nl =
        static_cast<const char*>(std::memchr(from + scanned, '\n', end_ - begin_ - scanned));
    const std::size_t length = nl ? static_cast<std::size_t>(nl - from) : end_ - begin_;
    if (length > max_) return cut_overlong(line);
    if (nl) {
      begin_ += length + 1;
      return give({from, length}, line);
    }
    scanned = length;
    if (!fill()) {  // the end of the input or a read error
      if (!error_.empty() || begin_ == end_) return false;
      const std::string_view last(block_.data() + begin_, end_ - begin_);
      begin_ = end_;
      return give(last, line);  // the last line, without its '\n'
    }
  }
}

/// Keeps the first max_ bytes of the line at begin_ and skips the rest of it.
bool LineReader::cut_overlong(std::string_view* line) {
  cut_.assign(block_.data() + begin_, max_);
  begin_ += max_;
  for (;;) {
    const char* from = block_.data() + begin_;
    const auto* nl = static_cast<const char*>(std::memchr(from, '\n', end_ - begin_));
    if (nl) {
      begin_ += static_cast<std::size_t>(nl - from) + 1;
      break;
    }
    begin_ = end_;
    if (!fill()) {
      if (!error_.empty()) return false;
      break;  // the long line was the last
    }
  }
  overlong_ = true;
  return give(cut_, line);
}

bool LineReader::give(std::string_view text, std::string_view* line) {
  if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
  *line = text;
  ++line_number_;
  return true;
}

/// Appends what the stream's buffer holds (after at most one read of the file when it holds
/// nothing): false at the end of the input, or after a read error (error_ set).
bool LineReader::fill() {
  if (begin_ > 0) {  // the unread bytes move to the front
    std::memmove(block_.data(), block_.data() + begin_, end_ - begin_);
    end_ -= begin_;
    begin_ = 0;
  }
  std::streambuf* buf = in_->rdbuf();
  try {
    errno = 0;
    if (buf->sgetc() == std::char_traits<char>::eof()) {
      // libstdc++'s filebuf throws on a read error; other buffers may only set errno.
      if (errno != 0 && errno != EAGAIN) error_ = std::strerror(errno);
      return false;
    }
    // At least the byte sgetc() saw (an unbuffered streambuf tells 0 or -1 available).
    const std::streamsize ready = std::max<std::streamsize>(buf->in_avail(), 1);
    const auto room = static_cast<std::streamsize>(block_.size() - end_);
    end_ += static_cast<std::size_t>(buf->sgetn(block_.data() + end_, std::min(ready, room)));
    return true;
  } catch (const std::ios_base::failure& e) {
    error_ = read_failure(e);
    in_->setstate(std::ios::badbit);
    return false;
  }
}

}  // namespace vmass::io
