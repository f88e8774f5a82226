// Vector ASC reader (see include/vmass/can/asc_log.hpp).
#include "vmass/can/asc_log.hpp"

#include <array>

#include "log_tokens.hpp"

namespace vmass::can {
namespace {

using detail::Tokens;

CandumpLine corrupt(std::string* error, const char* why) {
  if (error) *error = why;
  return CandumpLine::kCorrupt;
}

bool starts_with(std::string_view s, std::string_view prefix) {
  return s.substr(0, prefix.size()) == prefix;
}

bool is_digits(std::string_view s) {
  if (s.empty()) return false;
  for (char c : s) {
    if (c < '0' || c > '9') return false;
  }
  return true;
}

/// "1A2x" (29-bit) or "1A2" (11-bit) in the log's base into the frame's id and flags.
bool parse_asc_id(std::string_view token, int base, CanFrame* f) {
  const bool extended = !token.empty() && (token.back() == 'x' || token.back() == 'X');
  if (extended) token.remove_suffix(1);
  std::uint32_t id = 0;
  const std::uint32_t max = extended ? kEffMask : kSffMask;
  const bool ok =
      base == 16 ? detail::parse_hex(token, max, &id) : detail::parse_dec(token, max, &id);
  if (!ok) return false;
  f->id = id;
  f->flags = extended ? kExtended : 0;
  return true;
}

constexpr std::uint32_t kMaxAscChannel = 255;

bool is_direction(std::string_view s) { return s == "Rx" || s == "Tx"; }

/// True when the token after a classic line's channel is a CAN id in the log's base, not an
/// event's word ("Statistic:", "SV:", "J1939TP", ...).
bool is_frame_word(std::string_view word, int base, CanFrame* scratch) {
  if (!word.empty() && word.back() == ':') return false;
  return parse_asc_id(word, base, scratch);
}

/// Payload length of a CAN FD DLC code.
int fd_length_of_dlc(std::uint32_t dlc) {
  static constexpr std::array<int, 16> kLength = {0, 1,  2,  3,  4,  5,  6,  7,
                                                  8, 12, 16, 20, 24, 32, 48, 64};
  return dlc < kLength.size() ? kLength[dlc] : -1;
}

/// Classic frame after the channel: ID DIR d|r DLC BYTES... (extra text after the bytes).
CandumpLine parse_classic(const Tokens& t, int base, CanFrame* f, std::string* error) {
  if (!parse_asc_id(t[2], base, f)) return corrupt(error, "CAN id is not valid in the log's base");
  if (t[3] != "Rx" && t[3] != "Tx") return corrupt(error, "expected Rx or Tx after the CAN id");
  std::uint32_t dlc = 0;
  if (t[4] == "r") {
    f->flags = static_cast<std::uint8_t>(f->flags | kRemote);
    if (t.count > 5 && detail::parse_hex(t[5], 0xF, &dlc)) {
      f->len = static_cast<std::uint8_t>(dlc > 8 ? 8 : dlc);
    }
    return CandumpLine::kFrame;
  }
  if (t[4] != "d") return corrupt(error, "expected d (data) or r (remote) after the direction");
  if (!detail::parse_hex(t[5], 0xF, &dlc)) return corrupt(error, "DLC is not a digit 0..F");
  const std::size_t len = dlc > 8 ? 8 : dlc;
  if (!detail::parse_bytes(t, 6, len, base, f)) {
    return corrupt(error, "fewer data bytes than the DLC says, or a byte that is not a number");
  }
  return CandumpLine::kFrame;
}

/// CAN FD after "CANFD": CH DIR ID [NAME] BRS ESI DLC LEN BYTES...
CandumpLine parse_fd(const Tokens& t, int base, CanFrame* f, std::string* error) {
  if (t[4] == "ErrorFrame") {
    f->flags = kError;
    return CandumpLine::kFrame;
  }
  if (!parse_asc_id(t[4], base, f)) return corrupt(error, "CAN FD id is not valid");
  std::size_t k = 5;
  if (t[k] != "0" && t[k] != "1") ++k;  // a symbolic name
  if ((t[k] != "0" && t[k] != "1") || (t[k + 1] != "0" && t[k + 1] != "1")) {
    return corrupt(error, "expected the CAN FD BRS and ESI bits (0 or 1)");
  }
  std::uint32_t dlc = 0, len = 0;
  if (!detail::parse_hex(t[k + 2], 0xF, &dlc) || !detail::parse_dec(t[k + 3], 64, &len) ||
      fd_length_of_dlc(dlc) != static_cast<int>(len)) {
    return corrupt(error, "CAN FD DLC and data length do not agree");
  }
  f->flags = static_cast<std::uint8_t>(f->flags | kFd | (t[k] == "1" ? kFdBrs : 0) |
                                       (t[k + 1] == "1" ? kFdEsi : 0));
  if (!detail::parse_bytes(t, k + 4, len, base, f)) {
    return corrupt(error, "fewer CAN FD data bytes than the data length says");
  }
  return CandumpLine::kFrame;
}

int month_number(std::string_view name) {
  static constexpr std::array<std::string_view, 12> kMonths = {
      "Jan", "Feb", "Mar", "Apr", "May", "Jun", "Jul", "Aug", "Sep", "Oct", "Nov", "Dec"};
  for (std::size_t i = 0; i < kMonths.size(); ++i) {
    if (name == kMonths[i]) return static_cast<int>(i) + 1;
  }
  return 0;
}

}  // namespace

bool parse_asc_date(std::string_view text, std::int64_t* time_us) {
  // WEEKDAY MONTH DAY HH:MM:SS[.mmm] [am|pm] YEAR
  const Tokens t = detail::split_blanks(text);
  const bool has_ampm =
      t.count == 6 && (t[4] == "am" || t[4] == "pm" || t[4] == "AM" || t[4] == "PM");
  if (t.count != (has_ampm ? 6u : 5u)) return false;
  const int month = month_number(t[1]);
  std::uint32_t day = 0, year = 0, hour = 0, minute = 0;
  const std::string_view clock = t[3];
  std::int64_t second_ms = 0;
  const std::string_view sec_text = clock.size() > 6 ? clock.substr(6) : "";
  const std::size_t dot = sec_text.find('.');
  std::uint32_t ms = 0, whole_s = 0;
  if (month == 0 || !detail::parse_dec(t[2], 31, &day) ||
      !detail::parse_dec(t[has_ampm ? 5 : 4], 9999, &year) || clock.size() < 8 || clock[2] != ':' ||
      clock[5] != ':' || !detail::parse_dec(clock.substr(0, 2), 23, &hour) ||
      !detail::parse_dec(clock.substr(3, 2), 59, &minute) ||
      !detail::parse_dec(sec_text.substr(0, dot), 60, &whole_s) ||
      (dot != std::string_view::npos && !detail::parse_dec(sec_text.substr(dot + 1), 999, &ms))) {
    return false;
  }
  if (has_ampm) hour = hour % 12 + ((t[4] == "pm" || t[4] == "PM") ? 12 : 0);
  second_ms = static_cast<std::int64_t>(whole_s) * 1000 + ms;  // the fraction is milliseconds
  const std::int64_t days = detail::days_from_civil(year, static_cast<unsigned>(month), day);
  *time_us = ((days * 24 + hour) * 60 + minute) * 60'000'000LL + second_ms * 1000;
  return true;
}

CandumpLine AscParser::parse(std::string_view line, CandumpRecord* record, std::string* error) {
  line = detail::trim(line);
  if (line.empty() || starts_with(line, "//")) return CandumpLine::kComment;
  if (line[0] >= '0' && line[0] <= '9') return parse_timed(line, record, error);
  return parse_header(line, error);
}

CandumpLine AscParser::parse_header(std::string_view line, std::string* error) {
  const Tokens t = detail::split_blanks(line);
  if (t[0] == "date" || (t[0] == "Begin" && (t[1] == "Triggerblock" || t[1] == "TriggerBlock"))) {
    const bool trigger = t[0] == "Begin";
    const std::string_view date =
        detail::trim(line.substr(line.find(t[trigger ? 1 : 0]) + t[trigger ? 1 : 0].size()));
    if (date.empty() || (have_trigger_date_ && !trigger)) return CandumpLine::kComment;
    if (!parse_asc_date(date, &start_us_)) {
      return corrupt(error,
                     "date not understood (e.g. 'Wed Jan 10 10:55:25.123 am 2024'): "
                     "times count from the previous date, or 0");
    }
    have_trigger_date_ = have_trigger_date_ || trigger;
    return CandumpLine::kComment;
  }
  if (t[0] == "base") {
    if ((t[1] != "hex" && t[1] != "dec") || t[2] != "timestamps" ||
        (t[3] != "absolute" && t[3] != "relative")) {
      return corrupt(error, "expected 'base hex|dec  timestamps absolute|relative'");
    }
    base_ = t[1] == "hex" ? 16 : 10;
    relative_ = t[3] == "relative";
    return CandumpLine::kComment;
  }
  if (t[0] == "End" || (t[0] == "internal" && t[1] == "events") ||
      (t[0] == "no" && t[1] == "internal")) {
    return CandumpLine::kComment;
  }
  return corrupt(error, "expected a time, a header (date, base, Begin/End Triggerblock) or //");
}

CandumpLine AscParser::parse_timed(std::string_view line, CandumpRecord* record,
                                   std::string* error) {
  const Tokens t = detail::split_blanks(line);
  std::int64_t offset_us = 0;
  if (!detail::parse_fixed(t[0], 6, &offset_us)) return corrupt(error, "time is not a number");
  if (relative_) offset_us += last_offset_us_;
  last_offset_us_ = offset_us;
  if (t.count < 2) return corrupt(error, "a time and nothing after it");
  const bool fd = t[1] == "CANFD";
  const std::string_view channel = fd ? t[2] : t[1];
  // A line is an event only when it names no channel ("Start of measurement", "CAN 1 Status:")
  // or its channel carries words, not a frame ("1 Statistic: ...", "1 SV: ...", "1 J1939TP ...");
  // every other line is a frame, read or counted as corrupt, never dropped silently.
  const bool frame_like = fd || t[2] == "ErrorFrame" || is_direction(t[2]) || is_direction(t[3]);
  if (!is_digits(channel) && !frame_like) return CandumpLine::kComment;
  std::uint32_t ch = 0;
  if (!is_digits(channel)) return corrupt(error, "channel is not a number");
  if (!detail::parse_dec(channel, kMaxAscChannel, &ch)) return corrupt(error, "channel above 255");
  if (t.count < 3) return corrupt(error, "nothing after the channel");
  CanFrame f;
  if (!frame_like && !is_frame_word(t[2], base_, &f)) {
    return CandumpLine::kComment;  // a channel event
  }
  f = CanFrame{};
  f.time_us = start_us_ + offset_us;
  CandumpLine kind = CandumpLine::kFrame;
  if (!fd && t[2] == "ErrorFrame") {
    f.flags = kError;
  } else {
    kind = fd ? parse_fd(t, base_, &f, error) : parse_classic(t, base_, &f, error);
  }
  if (kind != CandumpLine::kFrame) return kind;
  interface_ = "can" + std::to_string(ch > 0 ? ch - 1 : 0);
  if (record) {
    record->frame = f;
    record->interface = interface_;
    record->direction = '\0';
  }
  return CandumpLine::kFrame;
}

}  // namespace vmass::can
