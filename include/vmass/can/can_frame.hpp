// CanFrame: one CAN or CAN FD frame as the CAN layer passes it around, independent of where it
// came from (SocketCAN, a candump log, the simulator).
//
// The identifier is stored without flag bits (11 or 29 bits); whether it is a 29-bit extended
// identifier, an FD frame, a remote request or an error frame is in `flags`. For an error frame,
// `id` holds the error class bits (linux/can/error.h, CAN_ERR_MASK) and `data` the details.
// `time_us` is in microseconds (LCM `utime` convention): kernel receive time for SocketCAN, the
// log's timestamp for candump logs. Plain value type; thread-safe to copy.
#pragma once

#include <cstdint>

namespace vmass::can {

constexpr std::uint32_t kSffMask = 0x7FFu;              ///< 11-bit identifier mask
constexpr std::uint32_t kEffMask = 0x1FFFFFFFu;         ///< 29-bit identifier mask
constexpr std::uint32_t kDbcExtendedBit = 0x80000000u;  ///< DBC BO_ ids: bit 31 = extended
constexpr int kClassicMaxLen = 8;
constexpr int kFdMaxLen = 64;

/// Frame flag bits (CanFrame::flags).
enum FrameFlag : std::uint8_t {
  kExtended = 1u << 0,  ///< 29-bit identifier
  kFd = 1u << 1,        ///< CAN FD frame
  kFdBrs = 1u << 2,     ///< CAN FD bit-rate switch (CANFD_BRS)
  kFdEsi = 1u << 3,     ///< CAN FD error state indicator (CANFD_ESI)
  kRemote = 1u << 4,    ///< remote transmission request (classic only)
  kError = 1u << 5,     ///< error frame: id holds error class bits
  kFdFdf = 1u << 6,     ///< CAN FD frame-format flag (CANFD_FDF), as newer kernels report it
};

struct CanFrame {
  std::int64_t time_us = 0;  ///< receive time, microseconds
  std::uint32_t id = 0;      ///< 11- or 29-bit identifier, no flag bits
  std::uint8_t flags = 0;    ///< FrameFlag bits
  std::uint8_t len = 0;      ///< payload length in bytes, 0..8 classic, 0..64 FD
  std::uint8_t data[kFdMaxLen] = {};

  bool extended() const { return (flags & kExtended) != 0; }
  bool fd() const { return (flags & kFd) != 0; }
  bool remote() const { return (flags & kRemote) != 0; }
  bool error() const { return (flags & kError) != 0; }
};

/// Valid CAN FD payload lengths are 0..8, 12, 16, 20, 24, 32, 48, 64.
constexpr bool is_valid_fd_length(int len) {
  return (len >= 0 && len <= 8) || len == 12 || len == 16 || len == 20 || len == 24 || len == 32 ||
         len == 48 || len == 64;
}

}  // namespace vmass::can
