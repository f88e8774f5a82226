// End-to-end checksum algorithms, by name, and the place to add a vehicle's own.
//
// A message's checksum is computed over its covered payload bytes b_0..b_n-1 (in payload
// order), preceded by its data id when it has one (the low byte, then the high byte when the
// id is above 0xFF: AUTOSAR E2E profile 1's "both bytes" mode), and compared with the checksum
// signal's raw value, `bits` wide:
//
//   crc8_sae_j1850   CRC-8, polynomial 0x1D, initial 0xFF, final XOR 0xFF, not reflected
//                    (SAE J1850, AUTOSAR Crc_CalculateCRC8; CRC of "123456789" is 0x4B)
//   xor              d_lo ^ d_hi ^ b_0 ^ ... ^ b_n-1; below 8 bits the byte is folded by XOR of
//                    its bits-wide groups (a nibble checksum: low nibble ^ high nibble)
//   additive         (d_lo + d_hi + b_0 + ... + b_n-1) mod 2^bits
//
// A vehicle whose ECUs use their own scheme registers it once at start-up, before any config
// is read:   register_checksum({"acme_sum7", &acme_sum7, "ACME: ..."});
//
// Thread-safety: compute functions are pure and reentrant; register_checksum must run before
// any lookup from another thread (configuration time).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace vmass::can {

struct ChecksumInput {
  const std::uint8_t* bytes = nullptr;  ///< the covered payload bytes, in order
  std::size_t size = 0;
  std::uint32_t data_id = 0;
  bool has_data_id = false;
  int bits = 8;  ///< width of the checksum signal, 1..64
};

/// The checksum of the input, in its low `bits` bits.
using ChecksumFunction = std::uint64_t (*)(const ChecksumInput& input);

struct ChecksumAlgorithm {
  std::string_view name;
  ChecksumFunction compute = nullptr;
  std::string_view description;
  int required_bits = 0;  ///< a width the algorithm needs (8 for CRC-8), 0: any
};

/// The algorithm registered under this name, or nullptr.
const ChecksumAlgorithm* find_checksum(std::string_view name);
/// Adds an algorithm; false when the name is taken (nothing changes then).
bool register_checksum(const ChecksumAlgorithm& algorithm);
/// "crc8_sae_j1850, xor, additive, ..." for messages.
std::string checksum_names();

std::uint64_t crc8_sae_j1850(const ChecksumInput& input);
std::uint64_t xor_checksum(const ChecksumInput& input);
std::uint64_t additive_checksum(const ChecksumInput& input);

}  // namespace vmass::can
