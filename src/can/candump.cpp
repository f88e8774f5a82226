// candump -l log reader and writer (see include/vmass/can/candump.hpp).
#include "vmass/can/candump.hpp"

#include <charconv>
#include <istream>
#include <ostream>

namespace vmass::can {
namespace {

constexpr std::uint32_t kErrFlag = 0x20000000u;  // CAN_ERR_FLAG
constexpr std::uint32_t kErrMask = 0x1FFFFFFFu;  // CAN_ERR_MASK

/// The value of each byte as a hex digit, -1 for a byte that is none: one load per digit
/// instead of three range tests (the digits are most of a line).
struct HexDigits {
  std::int8_t value[256];
  constexpr HexDigits() : value() {
    for (int c = 0; c < 256; ++c) value[c] = -1;
    for (int d = 0; d < 10; ++d) value['0' + d] = static_cast<std::int8_t>(d);
    for (int d = 0; d < 6; ++d) {
      value['A' + d] = static_cast<std::int8_t>(10 + d);
      value['a' + d] = static_cast<std::int8_t>(10 + d);
    }
  }
};
constexpr HexDigits kHexDigits;

int hex_value(char c) { return kHexDigits.value[static_cast<unsigned char>(c)]; }

bool is_digit(char c) { return static_cast<unsigned>(c - '0') < 10u; }

bool is_blank(char c) { return c == ' ' || c == '\t'; }

CandumpLine corrupt(std::string* error, const char* why) {
  if (error) *error = why;
  return CandumpLine::kCorrupt;
}

// Each part of a line: nullptr when it parsed, else why the line is corrupt.

/// The decimal digits from line[*p] (*p moves past them all): how many, and in *value the number
/// their first max_kept make (exact integer arithmetic; more digits are an error to the caller).
std::size_t read_digits(std::string_view line, std::size_t* p, std::size_t max_kept,
                        std::int64_t* value) {
  const std::size_t begin = *p;
  std::size_t q = begin;
  std::int64_t v = 0;
  for (; q < line.size() && is_digit(line[q]); ++q) {
    if (q - begin < max_kept) v = v * 10 + (line[q] - '0');
  }
  *p = q;
  *value = v;
  return q - begin;
}

/// (SECONDS.FRACTION): 1..12 digits, then 6 or 9 fractional digits (9: nanoseconds).
const char* parse_timestamp(std::string_view line, std::size_t* at, std::int64_t* time_us) {
  std::size_t p = *at;
  if (line[p] != '(') return "expected '(' opening the timestamp";
  ++p;
  if (p < line.size() && line[p] == '-') {
    return "negative time (before 1970): candump -l times are seconds since 1970";
  }
  std::int64_t sec = 0;
  const std::size_t sec_digits = read_digits(line, &p, 12, &sec);
  if (sec_digits == 0) return "expected seconds in the timestamp";
  if (sec_digits > 12) return "more than 12 digits of seconds in the timestamp";
  if (p >= line.size() || line[p] != '.') return "expected '.' in the timestamp";
  ++p;
  std::int64_t frac = 0;
  const std::size_t frac_digits = read_digits(line, &p, 9, &frac);
  if (frac_digits != 6 && frac_digits != 9) return "timestamp needs 6 or 9 fractional digits";
  if (p >= line.size() || line[p] != ')') return "expected ')' after the timestamp";
  if (frac_digits == 9) frac /= 1000;
  *time_us = sec * 1000000 + frac;
  *at = p + 1;
  return nullptr;
}

/// INTERFACE FRAME [R|T]: the interface name, the frame token and the optional direction.
const char* split_fields(std::string_view line, std::size_t p, std::string_view* iface,
                         std::string_view* frame, char* direction) {
  if (p >= line.size() || !is_blank(line[p])) return "expected a blank after ')'";
  while (p < line.size() && is_blank(line[p])) ++p;
  const std::size_t if_begin = p;
  while (p < line.size() && !is_blank(line[p])) ++p;
  if (p == if_begin) return "expected an interface name";
  *iface = line.substr(if_begin, p - if_begin);
  while (p < line.size() && is_blank(line[p])) ++p;
  std::size_t end = p;
  while (end < line.size() && !is_blank(line[end])) ++end;
  *frame = line.substr(p, end - p);
  std::size_t q = end;
  while (q < line.size() && is_blank(line[q])) ++q;
  *direction = '\0';
  if (q < line.size()) {
    if (q + 1 != line.size() || (line[q] != 'R' && line[q] != 'T')) {
      return "unexpected text after the frame";
    }
    *direction = line[q];
  }
  if (frame->empty()) return "expected a frame after the interface";
  return nullptr;
}

/// The id before '#': 3 hex digits (11 bit), or 8 (29 bit, or an error frame's class).
const char* parse_id(std::string_view tok, std::size_t hash, CanFrame* f) {
  if (hash == std::string_view::npos) return "expected '#' after the CAN id";
  if (hash != 3 && hash != 8) return "CAN id must have 3 or 8 hex digits";
  std::uint32_t id = 0;
  for (std::size_t i = 0; i < hash; ++i) {
    const int h = hex_value(tok[i]);
    if (h < 0) return "CAN id is not hexadecimal";
    id = (id << 4) | static_cast<std::uint32_t>(h);
  }
  if (hash == 3) {
    if (id > kSffMask) return "11-bit CAN id above 7FF";
    f->id = id;
  } else if (id & kErrFlag) {
    if (id & ~(kErrFlag | kErrMask)) return "error frame id has extra flag bits";
    f->id = id & kErrMask;
    f->flags = kError;
  } else {
    if (id > kEffMask) return "29-bit CAN id above 1FFFFFFF";
    f->id = id;
    f->flags = kExtended;
  }
  return nullptr;
}

/// After '##': the CAN FD flags digit (BRS, ESI, FDF).
const char* parse_fd_flags(std::string_view tok, std::size_t* d, CanFrame* f) {
  if (f->flags & kError) return "error frames are not CAN FD";
  ++*d;
  if (*d >= tok.size()) return "expected the CAN FD flags digit after '##'";
  const int fl = hex_value(tok[*d]);
  if (fl < 0) return "CAN FD flags digit is not hexadecimal";
  f->flags = static_cast<std::uint8_t>(f->flags | kFd | ((fl & 1) ? kFdBrs : 0) |
                                       ((fl & 2) ? kFdEsi : 0) | ((fl & 4) ? kFdFdf : 0));
  ++*d;
  return nullptr;
}

/// After '#R': a remote request, with an optional length digit.
const char* parse_remote(std::string_view tok, std::size_t d, CanFrame* f) {
  if (f->flags & kError) return "error frames have no remote form";
  ++d;
  f->flags = static_cast<std::uint8_t>(f->flags | kRemote);
  if (d < tok.size()) {
    const int l = hex_value(tok[d]);
    if (l < 0 || l > kClassicMaxLen || d + 1 != tok.size()) {
      return "remote frame length must be one digit 0..8";
    }
    f->len = static_cast<std::uint8_t>(l);
  }
  return nullptr;
}

/// The data bytes from tok[d]: hex pairs, '.' separators, a classic frame's "_D" raw DLC.
const char* parse_data(std::string_view tok, std::size_t d, int max_len, CanFrame* f) {
  int len = 0;
  while (d < tok.size()) {
    if (tok[d] == '.') {
      ++d;
      continue;
    }
    if (tok[d] == '_' && max_len == kClassicMaxLen && len == kClassicMaxLen) {
      // raw DLC 9..F of an 8-byte classic frame (len8_dlc)
      if (d + 2 != tok.size() || hex_value(tok[d + 1]) < 9) {
        return "expected '_' followed by a DLC digit 9..F";
      }
      break;
    }
    if (d + 1 >= tok.size()) return "odd number of hex digits in the data";
    const int hi = hex_value(tok[d]);
    const int lo = hex_value(tok[d + 1]);
    if (hi < 0 || lo < 0) return "data is not hexadecimal";
    if (len >= max_len) {
      return max_len == kFdMaxLen ? "more than 64 data bytes"
                                  : "more than 8 data bytes in a classic frame";
    }
    f->data[len++] = static_cast<std::uint8_t>(hi * 16 + lo);
    d += 2;
  }
  if ((f->flags & kFd) && !is_valid_fd_length(len)) {
    return "CAN FD length is not one of 0..8, 12, 16, 20, 24, 32, 48, 64";
  }
  f->len = static_cast<std::uint8_t>(len);
  return nullptr;
}

/// ID#DATA, ID##FDATA or ID#R[LEN].
const char* parse_frame(std::string_view tok, CanFrame* f) {
  const std::size_t hash = tok.find('#');
  if (const char* why = parse_id(tok, hash, f)) return why;
  std::size_t d = hash + 1;
  if (d < tok.size() && tok[d] == 'R') return parse_remote(tok, d, f);
  int max_len = kClassicMaxLen;
  if (d < tok.size() && tok[d] == '#') {
    if (const char* why = parse_fd_flags(tok, &d, f)) return why;
    max_len = kFdMaxLen;
  }
  return parse_data(tok, d, max_len, f);
}

}  // namespace

CandumpLine parse_candump_line(std::string_view line, CandumpRecord* record, std::string* error) {
  while (!line.empty() && (line.back() == '\r' || line.back() == '\n' || is_blank(line.back()))) {
    line.remove_suffix(1);
  }
  std::size_t p = 0;
  while (p < line.size() && is_blank(line[p])) ++p;
  if (p == line.size() || line[p] == '#' || line[p] == ';') return CandumpLine::kComment;
  CanFrame f;
  std::string_view iface, tok;
  char direction = '\0';
  if (const char* why = parse_timestamp(line, &p, &f.time_us)) return corrupt(error, why);
  if (const char* why = split_fields(line, p, &iface, &tok, &direction)) {
    return corrupt(error, why);
  }
  if (const char* why = parse_frame(tok, &f)) return corrupt(error, why);
  if (record) {
    record->frame = f;
    record->interface = iface;
    record->direction = direction;
  }
  return CandumpLine::kFrame;
}

std::size_t format_candump_line(const CanFrame& f, std::string_view interface, char* buf,
                                std::size_t capacity) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  const std::size_t need = 26 + interface.size() + 12 + 2 * kFdMaxLen + 2;
  if (capacity < need) return 0;
  std::int64_t t = f.time_us < 0 ? 0 : f.time_us;
  const std::int64_t sec = t / 1000000;
  const std::int64_t usec = t % 1000000;
  char* p = buf;
  // "(%010ld.%06ld) "
  *p++ = '(';
  char digits[24];
  const auto r = std::to_chars(digits, digits + sizeof digits, sec);
  const auto n = static_cast<std::size_t>(r.ptr - digits);
  for (std::size_t i = n; i < 10; ++i) *p++ = '0';
  for (std::size_t i = 0; i < n; ++i) *p++ = digits[i];
  *p++ = '.';
  std::int64_t div = 100000;
  for (int i = 0; i < 6; ++i, div /= 10) *p++ = static_cast<char>('0' + (usec / div) % 10);
  *p++ = ')';
  *p++ = ' ';
  for (char c : interface) *p++ = c;
  *p++ = ' ';
  auto put_id = [&](std::uint32_t id, int width) {
    for (int i = width - 1; i >= 0; --i) *p++ = kHex[(id >> (4 * i)) & 0xF];
  };
  if (f.error()) {
    put_id((f.id & kErrMask) | kErrFlag, 8);
  } else if (f.extended()) {
    put_id(f.id & kEffMask, 8);
  } else {
    put_id(f.id & kSffMask, 3);
  }
  *p++ = '#';
  const int max_len = f.fd() ? kFdMaxLen : kClassicMaxLen;
  const int len = f.len > max_len ? max_len : f.len;
  if (!f.fd() && f.remote()) {
    *p++ = 'R';
    if (f.len > 0 && f.len <= kClassicMaxLen) *p++ = kHex[f.len];
  } else {
    if (f.fd()) {
      *p++ = '#';
      *p++ = kHex[((f.flags & kFdBrs) ? 1 : 0) | ((f.flags & kFdEsi) ? 2 : 0) |
                  ((f.flags & kFdFdf) ? 4 : 0)];
    }
    for (int i = 0; i < len; ++i) {
      *p++ = kHex[f.data[i] >> 4];
      *p++ = kHex[f.data[i] & 0xF];
    }
  }
  *p++ = '\n';
  return static_cast<std::size_t>(p - buf);
}

std::string format_candump_line(const CanFrame& frame, std::string_view interface) {
  std::string s(26 + interface.size() + 12 + 2 * kFdMaxLen + 2, '\0');
  s.resize(format_candump_line(frame, interface, s.data(), s.size()));
  return s;
}

CandumpReader::CandumpReader(std::istream& in, std::string source)
    : lines_(in, kMaxLineBytes), source_(std::move(source)) {}

void CandumpReader::corrupt_line(const std::string& why) {
  ++stats_.corrupt;
  CandumpError e{line_no_, source_ + ":" + std::to_string(line_no_) + ": " + why};
  if (callback_) callback_(e);
  if (errors_.size() < kMaxKeptErrors) errors_.push_back(std::move(e));
}

bool CandumpReader::next(CandumpRecord* record) {
  CandumpRecord scratch;
  if (record == nullptr) record = &scratch;
  while (lines_.next(&line_)) {
    ++line_no_;
    ++stats_.lines;
    if (lines_.overlong()) {
      corrupt_line("line longer than " + std::to_string(kMaxLineBytes) + " bytes");
      continue;
    }
    switch (parse_candump_line(line_, record, &why_)) {
      case CandumpLine::kFrame:
        ++stats_.frames;
        if (record->frame.fd()) ++stats_.fd_frames;
        if (record->frame.remote()) ++stats_.remote_frames;
        if (record->frame.error()) ++stats_.error_frames;
        return true;
      case CandumpLine::kComment:
        ++stats_.comments;
        break;
      case CandumpLine::kCorrupt:
        corrupt_line(why_);
        break;
    }
  }
  if (!lines_.error().empty()) read_error_ = source_ + ": read error: " + lines_.error();
  return false;
}

void CandumpWriter::write(const CanFrame& frame, std::string_view interface) {
  char buf[512];
  if (interface.size() > 256) interface = interface.substr(0, 256);
  const std::size_t n = format_candump_line(frame, interface, buf, sizeof buf);
  out_.write(buf, static_cast<std::streamsize>(n));
}

}  // namespace vmass::can
