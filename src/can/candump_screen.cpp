// candump screen-output reader (see include/vmass/can/candump_screen.hpp).
#include "vmass/can/candump_screen.hpp"

#include "log_tokens.hpp"

namespace vmass::can {
namespace {

using detail::Tokens;

constexpr std::uint32_t kErrFlag = 0x20000000u;  // CAN_ERR_FLAG

CandumpLine corrupt(std::string* error, const char* why) {
  if (error) *error = why;
  return CandumpLine::kCorrupt;
}

/// Index of the "[LEN]" token, or 0 when there is none after an interface and an id.
std::size_t length_token(const Tokens& t, std::size_t first) {
  for (std::size_t i = first + 2; i < t.count; ++i) {
    const std::string_view s = t[i];
    if (s.size() >= 3 && s.front() == '[' && s.back() == ']') return i;
  }
  return 0;
}

/// "(SECONDS.FRACTION)" into *time_us.
bool parse_time(std::string_view token, std::int64_t* time_us) {
  if (token.size() < 3 || token.front() != '(' || token.back() != ')') return false;
  return detail::parse_fixed(token.substr(1, token.size() - 2), 6, time_us);
}

bool parse_id(std::string_view token, CanFrame* f) {
  std::uint32_t id = 0;
  if (token.size() == 3) {
    if (!detail::parse_hex(token, kSffMask, &id)) return false;
    f->id = id;
    return true;
  }
  if (token.size() != 8 || !detail::parse_hex(token, 0xFFFFFFFFu, &id)) return false;
  if (id & kErrFlag) {
    f->id = id & kEffMask;
    f->flags = kError;
  } else if (id <= kEffMask) {
    f->id = id;
    f->flags = kExtended;
  } else {
    return false;
  }
  return true;
}

}  // namespace

bool is_candump_screen_line(std::string_view line) {
  const Tokens t = detail::split_blanks(line);
  const std::size_t first = !t[0].empty() && t[0].front() == '(' ? 1 : 0;
  const std::size_t len_at = length_token(t, first);
  CanFrame f;
  return len_at != 0 && parse_id(t[len_at - 1], &f);
}

CandumpLine CandumpScreenParser::parse(std::string_view line, CandumpRecord* record,
                                       std::string* error) {
  line = detail::trim(line);
  if (line.empty() || line[0] == '#') return CandumpLine::kComment;
  const Tokens t = detail::split_blanks(line);
  CanFrame f;
  const bool timed = t[0].front() == '(';
  if (timed && t[0].substr(0, 2) == "(-") {
    return corrupt(error, "negative time (before 1970): candump times are seconds since 1970");
  }
  if (timed && !parse_time(t[0], &f.time_us)) {
    return corrupt(error, "time is not (SECONDS.FRACTION)");
  }
  if (!timed && require_time_) {
    return corrupt(error, "no time: record with candump -l (or candump -t a) to replay");
  }
  const std::size_t first = timed ? 1 : 0;
  const std::size_t len_at = length_token(t, first);
  if (len_at == 0) return corrupt(error, "expected 'INTERFACE ID [LENGTH] DATA'");
  if (!parse_id(t[len_at - 1], &f)) return corrupt(error, "CAN id must have 3 or 8 hex digits");
  std::uint32_t len = 0;
  const std::string_view len_text = t[len_at].substr(1, t[len_at].size() - 2);
  if (!detail::parse_dec(len_text, kFdMaxLen, &len)) return corrupt(error, "length is not 0..64");
  if (t[len_at + 1] == "remote" && t[len_at + 2] == "request") {
    f.flags = static_cast<std::uint8_t>(f.flags | kRemote);
    f.len = static_cast<std::uint8_t>(len > 8 ? 8 : len);
  } else if (!detail::parse_bytes(t, len_at + 1, len, 16, &f)) {
    return corrupt(error, "fewer data bytes than the length says, or a byte that is not hex");
  }
  if (len > static_cast<std::uint32_t>(kClassicMaxLen)) {
    if (!is_valid_fd_length(static_cast<int>(len))) return corrupt(error, "not a CAN FD length");
    f.flags = static_cast<std::uint8_t>(f.flags | kFd);
  }
  interface_ = std::string(t[first]);
  if (record) {
    record->frame = f;
    record->interface = interface_;
    record->direction = '\0';
  }
  return CandumpLine::kFrame;
}

}  // namespace vmass::can
