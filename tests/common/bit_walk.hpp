// The reference decoder of the CAN tests: walks a signal's bits one at a time by the DBC format's
// rules (Intel: start is the LSB, next bit b+1; Motorola: start is the MSB, next bit
// b%8==0 ? b+15 : b-1), then sign or float interpretation and scaling. Deliberately slow and
// plain: the compiled decoder's tables and word paths are checked against it.
#pragma once

#include <cstdint>
#include <cstring>

#include "vmass/can/dbc.hpp"

namespace vmass::testing {

/// The raw bits of s in data, MSB first for Motorola.
inline std::uint64_t walk_raw(const can::Signal& s, const std::uint8_t* data) {
  std::uint64_t v = 0;
  if (s.byte_order == can::ByteOrder::kIntel) {
    for (int i = 0; i < s.length; ++i) {
      const int b = s.start_bit + i;
      v |= static_cast<std::uint64_t>((data[b / 8] >> (b % 8)) & 1) << i;
    }
  } else {
    int b = s.start_bit;
    for (int i = 0; i < s.length; ++i) {
      v = (v << 1) | static_cast<std::uint64_t>((data[b / 8] >> (b % 8)) & 1);
      b = b % 8 == 0 ? b + 15 : b - 1;
    }
  }
  return v;
}

/// The physical value: raw bits as unsigned, signed or IEEE float, times factor plus offset.
inline double walk_physical(const can::Signal& s, const std::uint8_t* data) {
  const std::uint64_t u = walk_raw(s, data);
  double raw;
  if (s.value_type == can::ValueType::kFloat32) {
    const auto u32 = static_cast<std::uint32_t>(u);
    float f;
    std::memcpy(&f, &u32, 4);
    raw = f;
  } else if (s.value_type == can::ValueType::kFloat64) {
    std::memcpy(&raw, &u, 8);
  } else if (s.is_signed && s.length < 64 && ((u >> (s.length - 1)) & 1)) {
    raw = static_cast<double>(static_cast<std::int64_t>(u) - (std::int64_t{1} << (s.length - 1)) -
                              (std::int64_t{1} << (s.length - 1)));
  } else if (s.is_signed) {
    raw = static_cast<double>(static_cast<std::int64_t>(u));
  } else {
    raw = static_cast<double>(u);
  }
  return raw * s.factor + s.offset;
}

}  // namespace vmass::testing
