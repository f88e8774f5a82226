// SocketCanReader: frames from a Linux SocketCAN raw socket (classic and CAN FD), with kernel
// receive timestamps, drop and error-frame counters, and recovery when the interface goes down
// or disappears.
//
// - CAN FD: CAN_RAW_FD_FRAMES is enabled (ENOPROTOOPT tolerated: classic only); records are 16
//   (struct can_frame) or 72 bytes (struct canfd_frame), anything else is counted as malformed.
// - Time: SO_TIMESTAMPING (software receive stamp), falling back to SO_TIMESTAMP; a record with
//   neither is stamped with CLOCK_REALTIME on arrival and counted.
// - Drops: SO_RXQ_OVFL's cumulative count per socket, summed over re-created sockets.
// - Error frames (CAN_RAW_ERR_FILTER): bus-off, controller problems and restarts are counted and
//   the frame is returned with the kError flag.
// - ENETDOWN (interface down): the socket is kept; read() reports kInterfaceDown and frames
//   flow again once the interface is up. ENODEV (interface removed): the socket is closed and
//   re-created by name, with exponential backoff, until the interface is back.
//
// - Batches: the records waiting are received up to 32 at a time (recvmmsg) and handed out one
//   per read(), so a busy bus costs one system call per batch, not a poll and a recvmsg per
//   frame; a read() that finds nothing waiting polls until its timeout.
//
// The read loop works on any file descriptor carrying can_frame/canfd_frame records (a seam:
// unit tests use socketpair(AF_UNIX, SOCK_SEQPACKET)); opening and re-opening go through an
// Opener function, receiving through an optional RecvMsg function.
//
// Thread-safety: one thread per reader. Not copyable.
#pragma once

#include <sys/socket.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vmass/can/can_frame.hpp"
#include "vmass/can/dbc.hpp"

namespace vmass::can {

struct CanIdFilter {
  std::uint32_t id = 0;
  bool extended = false;
};

/// One filter per message of a database (the DBC ids to receive).
std::vector<CanIdFilter> filters_for(const Database& db);

struct SocketCanOptions {
  std::string interface = "can0";
  bool fd_frames = true;             ///< enable CAN_RAW_FD_FRAMES
  bool error_frames = true;          ///< receive error frames (CAN_RAW_ERR_FILTER, all classes)
  std::vector<CanIdFilter> filters;  ///< empty: receive every id
  int receive_buffer_bytes = 0;      ///< SO_RCVBUF; 0 keeps the system default
  int reopen_initial_ms = 100;       ///< first wait before re-creating a vanished socket
  int reopen_max_ms = 5000;          ///< backoff ceiling

  /// "" or a message naming the key and bound.
  std::string validate() const;
};

/// Creates, configures and binds a raw CAN socket. Returns the descriptor, or -1 with *error
/// saying why (a kernel without AF_CAN gives a clear message, not a crash).
int open_can_socket(const SocketCanOptions& options, std::string* error);

enum class ReadStatus : std::uint8_t {
  kFrame,          ///< *frame holds a frame
  kTimeout,        ///< nothing within the timeout
  kInterfaceDown,  ///< ENETDOWN: socket kept; call read() again
  kInterfaceGone,  ///< ENODEV: socket closed; read() re-creates it with backoff
  kReopening,      ///< no socket yet; the last attempt failed (see last_error())
  kClosed,         ///< end of stream on a non-CAN descriptor (the peer closed)
  kError,          ///< another receive error (see last_error()); socket kept
};

std::string_view read_status_name(ReadStatus status);

struct SocketCanStats {
  std::uint64_t frames = 0;  ///< all records returned, error frames included
  std::uint64_t fd_frames = 0;
  std::uint64_t error_frames = 0;
  std::uint64_t bus_off = 0;              ///< error frames with CAN_ERR_BUSOFF
  std::uint64_t controller_problems = 0;  ///< CAN_ERR_CRTL
  std::uint64_t restarts = 0;             ///< CAN_ERR_RESTARTED
  std::uint64_t dropped = 0;              ///< SO_RXQ_OVFL, summed over sockets
  std::uint64_t malformed = 0;            ///< records of a size other than 16 or 72 bytes
  std::uint64_t no_kernel_timestamp = 0;  ///< stamped in user space instead
  std::uint64_t interface_down = 0;       ///< ENETDOWN seen
  std::uint64_t interface_gone = 0;       ///< ENODEV seen
  std::uint64_t reopen_attempts = 0;
  std::uint64_t reopens = 0;  ///< successful re-creations
};

class SocketCanReader {
 public:
  /// Returns a new ready descriptor, or -1 and *error.
  using Opener = std::function<int(std::string* error)>;
  /// recvmsg(2) replacement for tests; empty means ::recvmsg.
  using RecvMsg = std::function<long(int fd, msghdr* msg, int flags)>;

  /// Opens `options.interface`; nullptr and *error when the socket cannot be made.
  static std::unique_ptr<SocketCanReader> open(const SocketCanOptions& options, std::string* error);

  /// Reads from `fd` (owned, closed by the destructor). `reopen` re-creates the descriptor
  /// after ENODEV; an empty Opener makes ENODEV final (kReopening forever).
  SocketCanReader(int fd, Opener reopen, int reopen_initial_ms = 100, int reopen_max_ms = 5000,
                  RecvMsg recv = {});
  ~SocketCanReader();
  SocketCanReader(const SocketCanReader&) = delete;
  SocketCanReader& operator=(const SocketCanReader&) = delete;

  /// The next record: one received earlier, else whatever is waiting, else waits up to
  /// timeout_ms (0: returns kTimeout at once when nothing is waiting). Never throws; never
  /// blocks longer than the timeout (plus one re-open attempt).
  ReadStatus read(CanFrame* frame, int timeout_ms);

  /// The parsing step of read(): one received record and its control messages.
  ReadStatus handle_record(const void* data, std::size_t size, const msghdr* msg, CanFrame* frame);

  const SocketCanStats& stats() const { return stats_; }
  const std::string& last_error() const { return last_error_; }
  int fd() const { return fd_; }

 private:
  using Clock = std::chrono::steady_clock;
  struct Batch;

  void close_fd();
  /// The next frame of the current batch (kFrame, or kClosed at the end of a stream); nullopt
  /// when the batch is used up.
  std::optional<ReadStatus> take_batched(CanFrame* frame);
  /// Receives the records waiting into the batch: kFrame (some), kTimeout (none), or the error.
  ReadStatus receive_batch();
  ReadStatus receive_error(int err);
  /// Without a socket: one re-open attempt when due, else sleeps toward the deadline; kReopening
  /// once it has passed, nullopt to go on.
  std::optional<ReadStatus> wait_for_socket(Clock::time_point deadline);

  std::unique_ptr<Batch> batch_;
  int batch_count_ = 0;
  int batch_next_ = 0;
  int fd_ = -1;
  Opener reopen_;
  RecvMsg recv_;
  int backoff_initial_ms_;
  int backoff_max_ms_;
  int backoff_ms_;
  Clock::time_point next_reopen_{};
  std::uint32_t last_overflow_ = 0;  ///< SO_RXQ_OVFL of the current socket
  SocketCanStats stats_;
  std::string last_error_;
};

}  // namespace vmass::can
