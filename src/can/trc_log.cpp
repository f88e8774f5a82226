// PEAK TRC reader (see include/vmass/can/trc_log.hpp).
#include "vmass/can/trc_log.hpp"

#include <cmath>
#include <cstdlib>

#include "log_tokens.hpp"

namespace vmass::can {
namespace {

using detail::Tokens;

CandumpLine corrupt(std::string* error, const char* why) {
  if (error) *error = why;
  return CandumpLine::kCorrupt;
}

constexpr std::string_view kColumnLetters = "NOTBIdRLlD";
enum Column : std::size_t { kN, kO, kT, kB, kI, kDir, kR, kL, kLen, kD };

/// Days since 1899-12-30 (the OLE date of ;$STARTTIME) to microseconds since 1970.
constexpr double kOleEpochToUnixDays = 25569.0;

/// "0123" (11-bit, up to 4 digits) or "18FF0000" (29-bit).
bool parse_trc_id(std::string_view token, CanFrame* f) {
  const bool extended = token.size() > 4;
  std::uint32_t id = 0;
  if (!detail::parse_hex(token, extended ? kEffMask : kSffMask, &id)) return false;
  f->id = id;
  f->flags = static_cast<std::uint8_t>(f->flags | (extended ? kExtended : 0));
  return true;
}

/// Payload length of a CAN FD DLC code (0..15).
int fd_length_of_dlc(std::uint32_t dlc) {
  static constexpr int kLength[16] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 16, 20, 24, 32, 48, 64};
  return dlc < 16 ? kLength[dlc] : -1;
}

/// ID DLC DATA... (or RTR) from token `id_at` on: the 1.x rows.
CandumpLine parse_v1_payload(const Tokens& t, std::size_t id_at, std::size_t dlc_at, CanFrame* f,
                             std::string* error) {
  if (!parse_trc_id(t[id_at], f)) return corrupt(error, "CAN id is not 1 to 8 hex digits");
  std::uint32_t dlc = 0;
  if (!detail::parse_dec(t[dlc_at], 8, &dlc)) return corrupt(error, "DLC is not 0..8");
  if (t[dlc_at + 1] == "RTR") {
    f->flags = static_cast<std::uint8_t>(f->flags | kRemote);
    f->len = static_cast<std::uint8_t>(dlc);
    return CandumpLine::kFrame;
  }
  if (!detail::parse_bytes(t, dlc_at + 1, dlc, 16, f)) {
    return corrupt(error, "fewer data bytes than the DLC says, or a byte that is not hex");
  }
  return CandumpLine::kFrame;
}

}  // namespace

CandumpLine TrcParser::parse(std::string_view line, CandumpRecord* record, std::string* error) {
  line = detail::trim(line);
  if (line.empty()) return CandumpLine::kComment;
  if (line[0] == ';') return parse_header(line, error);
  CanFrame f;
  std::uint32_t bus = 1;
  const CandumpLine kind =
      version_x10_ >= 20 ? parse_v2(line, &f, &bus, error) : parse_v1(line, &f, &bus, error);
  if (kind != CandumpLine::kFrame) return kind;
  interface_ = "can" + std::to_string(bus > 0 ? bus - 1 : 0);
  if (record) {
    record->frame = f;
    record->interface = interface_;
    record->direction = '\0';
  }
  return kind;
}

CandumpLine TrcParser::parse_header(std::string_view line, std::string* error) {
  const std::size_t eq = line.find('=');
  const std::string_view key = line.substr(0, eq);
  const std::string_view value = eq == std::string_view::npos ? "" : line.substr(eq + 1);
  if (key == ";$FILEVERSION") {
    const std::size_t dot = value.find('.');
    std::uint32_t major = 0, minor = 0;
    if (dot == std::string_view::npos || !detail::parse_dec(value.substr(0, dot), 9, &major) ||
        !detail::parse_dec(value.substr(dot + 1), 9, &minor) || major < 1 || major > 2) {
      return corrupt(error, "file version is not 1.0 to 2.1");
    }
    version_x10_ = static_cast<int>(major * 10 + minor);
  } else if (key == ";$STARTTIME") {
    const std::string text(value);
    char* end = nullptr;
    const double days = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(days)) {
      return corrupt(error, "start time is not a number of days");
    }
    start_us_ = std::llround((days - kOleEpochToUnixDays) * 86400e6);
  } else if (key == ";$COLUMNS") {
    column_.fill(-1);
    int index = 0;
    for (std::size_t p = 0; p <= value.size(); ++index) {
      const std::size_t comma = std::min(value.find(',', p), value.size());
      const std::string_view name = value.substr(p, comma - p);
      const std::size_t letter = kColumnLetters.find(name);
      if (name.size() == 1 && letter != std::string_view::npos) column_[letter] = index;
      p = comma + 1;
    }
    have_columns_ = column_[kO] >= 0 && column_[kT] >= 0 && column_[kI] >= 0 &&
                    (column_[kL] >= 0 || column_[kLen] >= 0) && column_[kD] >= 0;
    if (!have_columns_) return corrupt(error, "columns lack one of O, T, I, L or l, D");
  }
  return CandumpLine::kComment;
}

CandumpLine TrcParser::parse_v1(std::string_view line, CanFrame* f, std::uint32_t* bus,
                                std::string* error) {
  const Tokens t = detail::split_blanks(line);
  if (t[0].empty() || t[0].back() != ')') return corrupt(error, "expected the message number 'N)'");
  std::int64_t offset_us = 0;
  if (!detail::parse_fixed(t[1], 3, &offset_us)) return corrupt(error, "time offset is not ms");
  f->time_us = start_us_ + offset_us;
  if (version_x10_ == 10) return parse_v1_payload(t, 2, 3, f, error);
  const std::size_t type_at = version_x10_ >= 12 ? 3 : 2;  // 1.2 and 1.3: the bus first
  if (version_x10_ >= 12 && !detail::parse_dec(t[2], 16, bus)) {
    return corrupt(error, "bus is not a number");
  }
  if (t[type_at] == "Error") {
    f->flags = kError;
    return CandumpLine::kFrame;
  }
  if (t[type_at] == "Warng") return CandumpLine::kComment;  // a bus warning, no frame
  if (t[type_at] != "Rx" && t[type_at] != "Tx") {
    return corrupt(error, "message type is not Rx, Tx, Warng or Error");
  }
  const std::size_t id_at = type_at + 1;
  return parse_v1_payload(t, id_at, id_at + (version_x10_ >= 13 ? 2 : 1), f, error);
}

CandumpLine TrcParser::parse_v2(std::string_view line, CanFrame* f, std::uint32_t* bus,
                                std::string* error) {
  if (!have_columns_) return corrupt(error, "a 2.x file needs ;$COLUMNS before its rows");
  const Tokens t = detail::split_blanks(line);
  auto col = [&](Column c) { return column_[c] < 0 ? std::string_view() : t[column_[c]]; };
  std::int64_t offset_us = 0;
  if (!detail::parse_fixed(col(kO), 3, &offset_us)) return corrupt(error, "time offset is not ms");
  f->time_us = start_us_ + offset_us;
  if (column_[kB] >= 0 && !detail::parse_dec(col(kB), 16, bus)) {
    return corrupt(error, "bus is not a number");
  }
  const std::string_view type = col(kT);
  if (type == "ER") {
    f->flags = kError;
    return CandumpLine::kFrame;
  }
  const bool fd = type == "FD" || type == "FB" || type == "FE" || type == "BI";
  if (type == "ST" || type == "EC" || type == "EV") return CandumpLine::kComment;  // no frame
  if (!fd && type != "DT" && type != "RR") {
    return corrupt(error, "message type is not DT, FD, FB, FE, BI, RR, ER, ST, EC or EV");
  }
  if (!parse_trc_id(col(kI), f)) return corrupt(error, "CAN id is not 1 to 8 hex digits");
  std::uint32_t n = 0;
  const bool by_dlc = column_[kLen] < 0;
  if (!detail::parse_dec(by_dlc ? col(kL) : col(kLen), by_dlc ? 15 : 64, &n)) {
    return corrupt(error, "length is not a number");
  }
  const int len =
      by_dlc ? (fd ? fd_length_of_dlc(n) : (n > 8 ? 8 : static_cast<int>(n))) : static_cast<int>(n);
  f->flags = static_cast<std::uint8_t>(f->flags | (fd ? kFd : 0) |
                                       ((type == "FB" || type == "FE") ? kFdBrs : 0) |
                                       ((type == "FE" || type == "BI") ? kFdEsi : 0));
  if (type == "RR") {
    f->flags = static_cast<std::uint8_t>(f->flags | kRemote);
    f->len = static_cast<std::uint8_t>(len);
    return CandumpLine::kFrame;
  }
  if (len < 0 || !detail::parse_bytes(t, static_cast<std::size_t>(column_[kD]),
                                      static_cast<std::size_t>(len), 16, f)) {
    return corrupt(error, "fewer data bytes than the length says, or a byte that is not hex");
  }
  return CandumpLine::kFrame;
}

}  // namespace vmass::can
