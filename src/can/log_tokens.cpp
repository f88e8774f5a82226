#include "log_tokens.hpp"

namespace vmass::can::detail {
namespace {

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

int digit_value(char c, int base) {
  int v = -1;
  if (c >= '0' && c <= '9') v = c - '0';
  if (c >= 'A' && c <= 'F') v = c - 'A' + 10;
  if (c >= 'a' && c <= 'f') v = c - 'a' + 10;
  return v < base ? v : -1;
}

bool parse_unsigned(std::string_view s, int base, std::uint32_t max, std::uint32_t* value) {
  if (s.empty() || s.size() > 10) return false;
  std::uint64_t v = 0;
  for (char c : s) {
    const int d = digit_value(c, base);
    if (d < 0) return false;
    v = v * static_cast<std::uint64_t>(base) + static_cast<std::uint64_t>(d);
  }
  if (v > max) return false;
  *value = static_cast<std::uint32_t>(v);
  return true;
}

}  // namespace

Tokens split_blanks(std::string_view line) {
  Tokens t;
  std::size_t p = 0;
  while (p < line.size() && t.count < Tokens::kMaxTokens) {
    while (p < line.size() && is_blank(line[p])) ++p;
    const std::size_t begin = p;
    while (p < line.size() && !is_blank(line[p])) ++p;
    if (p > begin) t.token[t.count++] = line.substr(begin, p - begin);
  }
  return t;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_blank(s.back())) s.remove_suffix(1);
  while (!s.empty() && is_blank(s.front())) s.remove_prefix(1);
  return s;
}

bool parse_hex(std::string_view s, std::uint32_t max, std::uint32_t* value) {
  return parse_unsigned(s, 16, max, value);
}

bool parse_dec(std::string_view s, std::uint32_t max, std::uint32_t* value) {
  return parse_unsigned(s, 10, max, value);
}

bool parse_fixed(std::string_view s, int scale_digits, std::int64_t* value) {
  const std::size_t dot = s.find('.');
  const std::string_view whole = s.substr(0, dot);
  const std::string_view frac = dot == std::string_view::npos ? "" : s.substr(dot + 1);
  if (whole.empty() || whole.size() > 12 || (dot != std::string_view::npos && frac.empty())) {
    return false;
  }
  std::int64_t v = 0;
  for (char c : whole) {
    if (c < '0' || c > '9') return false;
    v = v * 10 + (c - '0');
  }
  for (int i = 0; i < scale_digits; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const char c = k < frac.size() ? frac[k] : '0';
    if (c < '0' || c > '9') return false;
    v = v * 10 + (c - '0');
  }
  for (std::size_t k = static_cast<std::size_t>(scale_digits); k < frac.size(); ++k) {
    if (frac[k] < '0' || frac[k] > '9') return false;
  }
  *value = v;
  return true;
}

bool parse_bytes(const Tokens& tokens, std::size_t first, std::size_t count, int base,
                 CanFrame* frame) {
  if (first + count > tokens.count || count > static_cast<std::size_t>(kFdMaxLen)) return false;
  for (std::size_t i = 0; i < count; ++i) {
    std::uint32_t b = 0;
    if (!parse_unsigned(tokens[first + i], base, 0xFF, &b)) return false;
    frame->data[i] = static_cast<std::uint8_t>(b);
  }
  frame->len = static_cast<std::uint8_t>(count);
  return true;
}

std::int64_t days_from_civil(std::int64_t year, unsigned month, unsigned day) {
  year -= month <= 2 ? 1 : 0;
  const std::int64_t era = (year >= 0 ? year : year - 399) / 400;
  const auto yoe = static_cast<unsigned>(year - era * 400);
  const unsigned doy = (153 * (month > 2 ? month - 3 : month + 9) + 2) / 5 + day - 1;
  const unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + static_cast<std::int64_t>(doe) - 719468;
}

}  // namespace vmass::can::detail
