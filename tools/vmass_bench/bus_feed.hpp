// BusFeed: a CAN bus at a realistic load, written as SocketCAN records (struct can_frame, 16
// bytes each) to a descriptor, as a SocketCAN socket delivers them to vmassd --can-fd: the
// frames of a drive's candump -l log at their own pace (looped when the run is longer), plus
// filler frames of ids the DBC does not know (`filler_ids` ids, each every `filler_period_ms`),
// which a bus carries for other ECUs and a reader without kernel filters sees. Every millisecond
// the frames that are due are sent at once (sendmmsg); a frame the socket cannot take (the
// daemon lags) is dropped and counted, as a CAN socket's receive queue would.
// Not thread-safe: one feeding thread.
#pragma once

#include <linux/can.h>
#include <sys/socket.h>

#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include "vmass/can/can_frame.hpp"

namespace vmass::bench {

struct BusFeedStats {
  std::uint64_t log_frames = 0;
  std::uint64_t filler_frames = 0;
  std::uint64_t dropped = 0;  ///< refused by a full socket
  double seconds = 0.0;       ///< fed for
};

class BusFeed {
 public:
  /// The log's frames (any time base) and the filler ids (unknown_ids()).
  BusFeed(std::vector<can::CanFrame> log_frames, std::vector<std::uint32_t> filler_ids,
          int filler_period_ms);

  /// Feeds `fd` from now until `stop` is set.
  void run(int fd, const std::atomic<bool>& stop);

  const BusFeedStats& stats() const { return stats_; }
  double filler_frames_per_s() const;

 private:
  void send_due(int fd, std::int64_t now_us);

  std::vector<can::CanFrame> log_;  ///< time_us relative to the first frame
  std::int64_t log_span_us_ = 1;
  std::vector<std::uint32_t> filler_ids_;
  std::int64_t filler_period_us_;
  std::size_t next_log_ = 0;
  std::int64_t log_offset_us_ = 0;  ///< start of the current loop of the log
  std::int64_t next_filler_us_ = 0;
  std::vector<can::CanFrame> due_;  ///< reused each millisecond, with the send buffers
  std::vector<can_frame> raw_;
  std::vector<iovec> iov_;
  std::vector<mmsghdr> msgs_;
  BusFeedStats stats_;
};

/// The frames of a candump -l log; "" or why it cannot be read.
std::string read_log_frames(const std::string& path, std::vector<can::CanFrame>* frames);

/// `count` standard ids that `is_known` (the DBC) rejects, from 0x100 upward.
template <class IsKnown>
std::vector<std::uint32_t> unknown_ids(int count, IsKnown is_known) {
  std::vector<std::uint32_t> ids;
  for (std::uint32_t id = 0x100; id <= can::kSffMask && static_cast<int>(ids.size()) < count;
       ++id) {
    if (!is_known(id)) ids.push_back(id);
  }
  return ids;
}

}  // namespace vmass::bench
