// CAN log format detection and the text formats' parsers (see include/vmass/can/log_format.hpp
// and log_line_parser.hpp).
#include "vmass/can/log_format.hpp"

#include "log_tokens.hpp"
#include "vmass/can/asc_log.hpp"
#include "vmass/can/candump_screen.hpp"
#include "vmass/can/log_line_parser.hpp"
#include "vmass/can/trc_log.hpp"

namespace vmass::can {
namespace {

bool starts_with(std::string_view s, std::string_view prefix) {
  return s.substr(0, prefix.size()) == prefix;
}

/// A TRC message row: "N)" first (1.x) or a number then a time (2.x).
bool is_trc_row(std::string_view line) {
  const detail::Tokens t = detail::split_blanks(line);
  std::int64_t v = 0;
  return t.count >= 4 && !t[0].empty() &&
         (t[0].back() == ')' || detail::parse_fixed(t[0], 0, &v)) &&
         detail::parse_fixed(t[1], 3, &v);
}

/// The text formats, from their first meaningful lines.
LogFormat detect_text(std::string_view head) {
  bool semicolon_comments = false;
  std::size_t p = 0;
  while (p < head.size()) {
    const std::size_t eol = std::min(head.find('\n', p), head.size());
    const std::string_view line = detail::trim(head.substr(p, eol - p));
    p = eol + 1;
    if (line.empty() || line[0] == '#') continue;
    if (starts_with(line, ";$FILEVERSION") || starts_with(line, ";$STARTTIME")) {
      return LogFormat::kTrc;
    }
    if (line[0] == ';') {
      semicolon_comments = true;
      continue;
    }
    if (line[0] == '(' && line.find('#') != std::string_view::npos) return LogFormat::kCandump;
    if (starts_with(line, "date ") || starts_with(line, "base ") || starts_with(line, "//") ||
        starts_with(line, "Begin Triggerblock") || starts_with(line, "Begin TriggerBlock")) {
      return LogFormat::kAsc;
    }
    if (is_candump_screen_line(line)) return LogFormat::kCandumpScreen;
    if (semicolon_comments && is_trc_row(line)) return LogFormat::kTrc;
    return LogFormat::kUnknown;
  }
  return semicolon_comments ? LogFormat::kTrc : LogFormat::kCandump;  // no frames: empty log
}

}  // namespace

LogFormat detect_log_format(std::string_view head) {
  if (starts_with(head, "LOGG")) return LogFormat::kBlf;
  if (starts_with(head, "MDF     ") || starts_with(head, "UnFinMF ")) {
    return head.size() > 8 && head[8] == '4' ? LogFormat::kMdf4 : LogFormat::kMdf3;
  }
  if (starts_with(head, "\xED\xA1\xDA\x01")) return LogFormat::kLcmLog;  // lcm-logger's sync word
  for (char c : head.substr(0, 512)) {
    if (c == '\0') return LogFormat::kUnknown;  // some other binary file
  }
  return detect_text(head);
}

std::string_view log_format_name(LogFormat format) {
  switch (format) {
    case LogFormat::kCandump:
      return "candump -l";
    case LogFormat::kCandumpScreen:
      return "candump screen output";
    case LogFormat::kAsc:
      return "Vector ASC";
    case LogFormat::kTrc:
      return "PEAK TRC";
    case LogFormat::kBlf:
      return "Vector BLF";
    case LogFormat::kMdf4:
      return "ASAM MDF4";
    case LogFormat::kLcmLog:
      return "LCM log";
    case LogFormat::kMdf3:
      return "MDF 3";
    case LogFormat::kUnknown:
      break;
  }
  return "unknown";
}

std::unique_ptr<LogLineParser> make_log_line_parser(LogFormat format, bool require_time) {
  switch (format) {
    case LogFormat::kCandump:
      return std::make_unique<CandumpLineParser>();
    case LogFormat::kCandumpScreen:
      return std::make_unique<CandumpScreenParser>(require_time);
    case LogFormat::kAsc:
      return std::make_unique<AscParser>();
    case LogFormat::kTrc:
      return std::make_unique<TrcParser>();
    default:
      return nullptr;
  }
}

}  // namespace vmass::can
