// Small locale-free helpers the text log parsers share (src/can only): splitting a line at
// blanks, hexadecimal and decimal fields, fixed-point times without a round trip through double.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "vmass/can/can_frame.hpp"

namespace vmass::can::detail {

/// Up to kMaxTokens blank-separated tokens of a line (the rest is ignored).
struct Tokens {
  static constexpr std::size_t kMaxTokens = 96;
  std::string_view token[kMaxTokens];
  std::size_t count = 0;
  std::string_view operator[](std::size_t i) const { return i < count ? token[i] : ""; }
};
Tokens split_blanks(std::string_view line);

/// Strips a trailing CR/LF and blanks.
std::string_view trim(std::string_view s);

/// Hexadecimal digits (no prefix) into *value; false when empty, not hex or above max.
bool parse_hex(std::string_view s, std::uint32_t max, std::uint32_t* value);
/// Decimal digits into *value; false when empty, not decimal or above max.
bool parse_dec(std::string_view s, std::uint32_t max, std::uint32_t* value);

/// A non-negative decimal number "123.456" as an integer in units of 10^-scale_digits (digits
/// beyond scale_digits truncated): parse_fixed("1.5", 6) = 1500000. False when malformed.
bool parse_fixed(std::string_view s, int scale_digits, std::int64_t* value);

/// The payload: `count` byte tokens starting at tokens[first], in base 16 or 10.
bool parse_bytes(const Tokens& tokens, std::size_t first, std::size_t count, int base,
                 CanFrame* frame);

/// Days since 1970-01-01 of a proleptic Gregorian date (Howard Hinnant's days_from_civil).
std::int64_t days_from_civil(std::int64_t year, unsigned month, unsigned day);

}  // namespace vmass::can::detail
