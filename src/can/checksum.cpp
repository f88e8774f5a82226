#include "vmass/can/checksum.hpp"

#include <deque>

namespace vmass::can {
namespace {

/// The data id's bytes that go first: its low byte, and its high byte when it has one.
int data_id_bytes(const ChecksumInput& in, std::uint8_t out[2]) {
  if (!in.has_data_id) return 0;
  out[0] = static_cast<std::uint8_t>(in.data_id & 0xFFu);
  out[1] = static_cast<std::uint8_t>((in.data_id >> 8) & 0xFFu);
  return in.data_id > 0xFFu ? 2 : 1;
}

std::uint64_t low_bits(std::uint64_t v, int bits) {
  return bits >= 64 ? v : v & ((std::uint64_t{1} << bits) - 1);
}

std::uint8_t crc8_step(std::uint8_t crc, std::uint8_t byte) {
  crc ^= byte;
  for (int k = 0; k < 8; ++k) {
    crc = (crc & 0x80u) != 0 ? static_cast<std::uint8_t>((crc << 1) ^ 0x1Du)
                             : static_cast<std::uint8_t>(crc << 1);
  }
  return crc;
}

std::deque<ChecksumAlgorithm>& registry() {  // a deque: pointers stay valid as it grows
  static std::deque<ChecksumAlgorithm> algorithms = {
      {"crc8_sae_j1850", &crc8_sae_j1850,
       "CRC-8 SAE J1850 (poly 0x1D, init 0xFF, xor-out 0xFF), data id bytes first", 8},
      {"xor", &xor_checksum, "XOR of the data id bytes and the covered bytes", 0},
      {"additive", &additive_checksum, "sum of the data id bytes and the covered bytes", 0},
  };
  return algorithms;
}

}  // namespace

std::uint64_t crc8_sae_j1850(const ChecksumInput& in) {
  std::uint8_t id[2];
  std::uint8_t crc = 0xFF;
  for (int i = 0, n = data_id_bytes(in, id); i < n; ++i) crc = crc8_step(crc, id[i]);
  for (std::size_t i = 0; i < in.size; ++i) crc = crc8_step(crc, in.bytes[i]);
  return static_cast<std::uint8_t>(crc ^ 0xFFu);
}

std::uint64_t xor_checksum(const ChecksumInput& in) {
  std::uint8_t id[2];
  std::uint8_t x = 0;
  for (int i = 0, n = data_id_bytes(in, id); i < n; ++i) x ^= id[i];
  for (std::size_t i = 0; i < in.size; ++i) x ^= in.bytes[i];
  if (in.bits >= 8) return x;
  std::uint64_t folded = 0;  // XOR of the byte's bits-wide groups
  for (int shift = 0; shift < 8; shift += in.bits) folded ^= (x >> shift);
  return low_bits(folded, in.bits);
}

std::uint64_t additive_checksum(const ChecksumInput& in) {
  std::uint8_t id[2];
  std::uint64_t sum = 0;
  for (int i = 0, n = data_id_bytes(in, id); i < n; ++i) sum += id[i];
  for (std::size_t i = 0; i < in.size; ++i) sum += in.bytes[i];
  return low_bits(sum, in.bits);
}

const ChecksumAlgorithm* find_checksum(std::string_view name) {
  for (const ChecksumAlgorithm& a : registry()) {
    if (a.name == name) return &a;
  }
  return nullptr;
}

bool register_checksum(const ChecksumAlgorithm& algorithm) {
  if (algorithm.compute == nullptr || find_checksum(algorithm.name) != nullptr) return false;
  registry().push_back(algorithm);
  return true;
}

std::string checksum_names() {
  std::string names;
  for (const ChecksumAlgorithm& a : registry()) {
    if (!names.empty()) names += ", ";
    names += a.name;
  }
  return names;
}

}  // namespace vmass::can
