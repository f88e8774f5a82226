// SocketCAN reader (see include/vmass/can/socketcan.hpp).
#include "vmass/can/socketcan.hpp"

#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <linux/errqueue.h>
#include <linux/net_tstamp.h>
#include <net/if.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <optional>
#include <thread>

namespace vmass::can {

std::vector<CanIdFilter> filters_for(const Database& db) {
  std::vector<CanIdFilter> out;
  out.reserve(db.messages.size());
  for (const Message& m : db.messages) out.push_back({m.id, m.extended});
  return out;
}

std::string SocketCanOptions::validate() const {
  if (interface.empty() || interface.size() >= IFNAMSIZ) {
    return "interface: name must have 1.." + std::to_string(IFNAMSIZ - 1) + " characters";
  }
  if (receive_buffer_bytes < 0) return "receive_buffer_bytes: must be >= 0";
  if (reopen_initial_ms < 1) return "reopen_initial_ms: must be >= 1";
  if (reopen_max_ms < reopen_initial_ms) return "reopen_max_ms: must be >= reopen_initial_ms";
  for (const CanIdFilter& f : filters) {
    if (f.id > (f.extended ? kEffMask : kSffMask)) {
      return "filters: id " + std::to_string(f.id) + " does not fit its id type";
    }
  }
  return "";
}

std::string_view read_status_name(ReadStatus status) {
  switch (status) {
    case ReadStatus::kFrame:
      return "frame";
    case ReadStatus::kTimeout:
      return "timeout";
    case ReadStatus::kInterfaceDown:
      return "interface down";
    case ReadStatus::kInterfaceGone:
      return "interface gone";
    case ReadStatus::kReopening:
      return "re-opening";
    case ReadStatus::kClosed:
      return "closed";
    case ReadStatus::kError:
      return "error";
  }
  return "?";
}

namespace {

constexpr std::uint8_t kCanFdFdf = 0x04;  // CANFD_FDF (linux/can.h since 5.14)

std::string errno_text(const char* what, int err) {
  return std::string(what) + ": " + std::strerror(err);
}

}  // namespace

int open_can_socket(const SocketCanOptions& options, std::string* error) {
  auto fail = [&](const std::string& why, int fd) {
    if (error) *error = options.interface + ": " + why;
    if (fd >= 0) ::close(fd);
    return -1;
  };
  if (const std::string v = options.validate(); !v.empty()) return fail(v, -1);
  const int fd = ::socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
  if (fd < 0) {
    const int err = errno;
    if (err == EAFNOSUPPORT) {
      return fail(
          "socket(AF_CAN) failed: address family not supported; this kernel has no SocketCAN "
          "(load the can and can_raw modules, or run on a kernel built with CONFIG_CAN)",
          -1);
    }
    return fail(errno_text("socket(AF_CAN)", err), -1);
  }
  const int one = 1;
  if (options.fd_frames &&
      ::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FD_FRAMES, &one, sizeof one) != 0 &&
      errno != ENOPROTOOPT) {  // ENOPROTOOPT: an old kernel without CAN FD; classic only
    return fail(errno_text("setsockopt(CAN_RAW_FD_FRAMES)", errno), fd);
  }
  if (!options.filters.empty()) {
    // CAN_RAW_FILTER_MAX is 512: beyond that receive everything (the decoder ignores the rest).
    if (options.filters.size() <= 512) {
      std::vector<can_filter> filters;
      filters.reserve(options.filters.size());
      for (const CanIdFilter& f : options.filters) {
        can_filter k{};
        if (f.extended) {
          k.can_id = f.id | CAN_EFF_FLAG;
          k.can_mask = CAN_EFF_MASK | CAN_EFF_FLAG | CAN_RTR_FLAG;
        } else {
          k.can_id = f.id;
          k.can_mask = CAN_SFF_MASK | CAN_EFF_FLAG | CAN_RTR_FLAG;
        }
        filters.push_back(k);
      }
      if (::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FILTER, filters.data(),
                       static_cast<socklen_t>(filters.size() * sizeof(can_filter))) != 0) {
        return fail(errno_text("setsockopt(CAN_RAW_FILTER)", errno), fd);
      }
    }
  }
  if (options.error_frames) {
    const can_err_mask_t mask = CAN_ERR_MASK;
    if (::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &mask, sizeof mask) != 0) {
      return fail(errno_text("setsockopt(CAN_RAW_ERR_FILTER)", errno), fd);
    }
  }
  // Drop counter and timestamps are best effort: the reader counts what it cannot get.
  (void)::setsockopt(fd, SOL_SOCKET, SO_RXQ_OVFL, &one, sizeof one);
  const int ts_flags = SOF_TIMESTAMPING_SOFTWARE | SOF_TIMESTAMPING_RX_SOFTWARE;
  if (::setsockopt(fd, SOL_SOCKET, SO_TIMESTAMPING, &ts_flags, sizeof ts_flags) != 0) {
    (void)::setsockopt(fd, SOL_SOCKET, SO_TIMESTAMP, &one, sizeof one);
  }
  if (options.receive_buffer_bytes > 0) {
    (void)::setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &options.receive_buffer_bytes,
                       sizeof options.receive_buffer_bytes);
  }
  const unsigned index = ::if_nametoindex(options.interface.c_str());
  if (index == 0) return fail("no such interface (" + std::string(std::strerror(errno)) + ")", fd);
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = static_cast<int>(index);
  if (::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
    return fail(errno_text("bind", errno), fd);
  }
  return fd;
}

/// Room for a batch of records and their control messages, reused for every recvmmsg.
struct SocketCanReader::Batch {
  static constexpr int kRecords = 32;
  static constexpr std::size_t kControlBytes = CMSG_SPACE(sizeof(scm_timestamping)) +
                                               CMSG_SPACE(sizeof(timeval)) +
                                               CMSG_SPACE(sizeof(std::uint32_t)) + 64;
  alignas(canfd_frame) unsigned char data[kRecords][sizeof(canfd_frame) + 8];
  alignas(cmsghdr) unsigned char control[kRecords][kControlBytes];
  iovec iov[kRecords];
  mmsghdr msgs[kRecords];

  /// Resets the headers the kernel writes into (lengths, flags).
  void prepare() {
    for (int i = 0; i < kRecords; ++i) {
      iov[i] = {data[i], sizeof data[i]};
      msgs[i] = {};
      msgs[i].msg_hdr.msg_iov = &iov[i];
      msgs[i].msg_hdr.msg_iovlen = 1;
      msgs[i].msg_hdr.msg_control = control[i];
      msgs[i].msg_hdr.msg_controllen = kControlBytes;
    }
  }
};

std::unique_ptr<SocketCanReader> SocketCanReader::open(const SocketCanOptions& options,
                                                       std::string* error) {
  const int fd = open_can_socket(options, error);
  if (fd < 0) return nullptr;
  return std::make_unique<SocketCanReader>(
      fd, [options](std::string* e) { return open_can_socket(options, e); },
      options.reopen_initial_ms, options.reopen_max_ms);
}

SocketCanReader::SocketCanReader(int fd, Opener reopen, int reopen_initial_ms, int reopen_max_ms,
                                 RecvMsg recv)
    : batch_(std::make_unique<Batch>()),
      fd_(fd),
      reopen_(std::move(reopen)),
      recv_(std::move(recv)),
      backoff_initial_ms_(std::max(1, reopen_initial_ms)),
      backoff_max_ms_(std::max(reopen_initial_ms, reopen_max_ms)),
      backoff_ms_(backoff_initial_ms_) {}

SocketCanReader::~SocketCanReader() { close_fd(); }

void SocketCanReader::close_fd() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  last_overflow_ = 0;
}

std::optional<ReadStatus> SocketCanReader::take_batched(CanFrame* frame) {
  while (batch_next_ < batch_count_) {
    const mmsghdr& m = batch_->msgs[batch_next_];
    const unsigned char* data = batch_->data[batch_next_];
    ++batch_next_;
    if (m.msg_len == 0) {  // end of stream (a socketpair's peer closed): no CAN record is empty
      batch_count_ = 0;
      return ReadStatus::kClosed;
    }
    if (m.msg_hdr.msg_flags & MSG_TRUNC) {
      ++stats_.malformed;
      continue;
    }
    if (handle_record(data, m.msg_len, &m.msg_hdr, frame) == ReadStatus::kFrame) {
      return ReadStatus::kFrame;
    }
  }
  return std::nullopt;
}

ReadStatus SocketCanReader::receive_error(int err) {
  if (err == ENETDOWN) {
    ++stats_.interface_down;
    last_error_ = "interface is down; waiting for it to come back";
    return ReadStatus::kInterfaceDown;
  }
  if (err == ENODEV || err == ENXIO) {
    ++stats_.interface_gone;
    close_fd();
    backoff_ms_ = backoff_initial_ms_;
    next_reopen_ = Clock::now() + std::chrono::milliseconds(backoff_ms_);
    last_error_ = "interface vanished; re-creating the socket";
    return ReadStatus::kInterfaceGone;
  }
  last_error_ = errno_text("recvmsg", err);
  return ReadStatus::kError;
}

ReadStatus SocketCanReader::receive_batch() {
  batch_->prepare();
  batch_count_ = 0;
  batch_next_ = 0;
  long n = 0;
  if (recv_) {  // the test seam: one record per call
    n = recv_(fd_, &batch_->msgs[0].msg_hdr, MSG_DONTWAIT);
    if (n >= 0) batch_->msgs[0].msg_len = static_cast<unsigned>(n);
    if (n >= 0) n = 1;
  } else {
    n = ::recvmmsg(fd_, batch_->msgs, Batch::kRecords, MSG_DONTWAIT, nullptr);
  }
  if (n < 0) {
    const int err = errno;
    if (err == EINTR || err == EAGAIN || err == EWOULDBLOCK) return ReadStatus::kTimeout;
    return receive_error(err);
  }
  batch_count_ = static_cast<int>(n);
  return ReadStatus::kFrame;
}

std::optional<ReadStatus> SocketCanReader::wait_for_socket(Clock::time_point deadline) {
  const Clock::time_point now = Clock::now();
  if (now >= next_reopen_ && reopen_) {
    ++stats_.reopen_attempts;
    std::string why;
    fd_ = reopen_(&why);
    if (fd_ >= 0) {
      ++stats_.reopens;
      backoff_ms_ = backoff_initial_ms_;
      last_overflow_ = 0;
      return std::nullopt;
    }
    last_error_ = why;
    next_reopen_ = now + std::chrono::milliseconds(backoff_ms_);
    backoff_ms_ = std::min(backoff_ms_ * 2, backoff_max_ms_);
  }
  const Clock::time_point wake = reopen_ ? std::min(next_reopen_, deadline) : deadline;
  if (wake > now) std::this_thread::sleep_for(wake - now);
  if (Clock::now() >= deadline) return ReadStatus::kReopening;
  return std::nullopt;
}

ReadStatus SocketCanReader::read(CanFrame* frame, int timeout_ms) {
  const Clock::time_point deadline = Clock::now() + std::chrono::milliseconds(timeout_ms);
  for (;;) {
    if (const std::optional<ReadStatus> st = take_batched(frame)) return *st;
    if (fd_ < 0) {
      if (const std::optional<ReadStatus> st = wait_for_socket(deadline)) return *st;
      continue;
    }
    // Whatever is waiting first (on a busy bus there always is): no poll() then.
    const ReadStatus got = receive_batch();
    if (got == ReadStatus::kFrame) continue;
    if (got != ReadStatus::kTimeout) return got;
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left <= 0) return ReadStatus::kTimeout;
    pollfd p{fd_, POLLIN, 0};
    const int pr = ::poll(&p, 1, static_cast<int>(left));
    if (pr < 0 && errno != EINTR) {
      last_error_ = errno_text("poll", errno);
      return ReadStatus::kError;
    }
    if (pr == 0) return ReadStatus::kTimeout;
  }
}

ReadStatus SocketCanReader::handle_record(const void* data, std::size_t size, const msghdr* msg,
                                          CanFrame* frame) {
  if (size != sizeof(can_frame) && size != sizeof(canfd_frame)) {
    ++stats_.malformed;
    return ReadStatus::kError;
  }
  canfd_frame raw{};
  std::memcpy(&raw, data, size);
  const bool is_fd = size == sizeof(canfd_frame);

  bool stamped = false;
  std::int64_t time_us = 0;
  if (msg != nullptr && msg->msg_controllen > 0) {
    for (cmsghdr* c = CMSG_FIRSTHDR(const_cast<msghdr*>(msg)); c != nullptr;
         c = CMSG_NXTHDR(const_cast<msghdr*>(msg), c)) {
      if (c->cmsg_level != SOL_SOCKET) continue;
      if (c->cmsg_type == SO_TIMESTAMPING && c->cmsg_len >= CMSG_LEN(sizeof(scm_timestamping))) {
        scm_timestamping ts;
        std::memcpy(&ts, CMSG_DATA(c), sizeof ts);
        const timespec& t = (ts.ts[0].tv_sec != 0 || ts.ts[0].tv_nsec != 0) ? ts.ts[0] : ts.ts[2];
        if (t.tv_sec != 0 || t.tv_nsec != 0) {
          time_us = static_cast<std::int64_t>(t.tv_sec) * 1000000 + t.tv_nsec / 1000;
          stamped = true;
        }
      } else if (c->cmsg_type == SO_TIMESTAMP && c->cmsg_len >= CMSG_LEN(sizeof(timeval))) {
        timeval tv;
        std::memcpy(&tv, CMSG_DATA(c), sizeof tv);
        time_us = static_cast<std::int64_t>(tv.tv_sec) * 1000000 + tv.tv_usec;
        stamped = true;
      } else if (c->cmsg_type == SO_RXQ_OVFL && c->cmsg_len >= CMSG_LEN(sizeof(std::uint32_t))) {
        std::uint32_t count;
        std::memcpy(&count, CMSG_DATA(c), sizeof count);
        if (count >= last_overflow_) stats_.dropped += count - last_overflow_;
        last_overflow_ = count;
      }
    }
  }
  if (!stamped) {
    timespec now{};
    ::clock_gettime(CLOCK_REALTIME, &now);
    time_us = static_cast<std::int64_t>(now.tv_sec) * 1000000 + now.tv_nsec / 1000;
    ++stats_.no_kernel_timestamp;
  }

  CanFrame f;
  f.time_us = time_us;
  const int max_len = is_fd ? kFdMaxLen : kClassicMaxLen;
  f.len = static_cast<std::uint8_t>(std::min<int>(raw.len, max_len));
  std::memcpy(f.data, raw.data, f.len);
  if (raw.can_id & CAN_ERR_FLAG) {
    f.flags = kError;
    f.id = raw.can_id & CAN_ERR_MASK;
    ++stats_.error_frames;
    if (f.id & CAN_ERR_BUSOFF) ++stats_.bus_off;
    if (f.id & CAN_ERR_CRTL) ++stats_.controller_problems;
    if (f.id & CAN_ERR_RESTARTED) ++stats_.restarts;
  } else if (raw.can_id & CAN_EFF_FLAG) {
    f.flags = kExtended;
    f.id = raw.can_id & CAN_EFF_MASK;
  } else {
    f.id = raw.can_id & CAN_SFF_MASK;
  }
  if (!is_fd && (raw.can_id & CAN_RTR_FLAG) && !(raw.can_id & CAN_ERR_FLAG)) {
    f.flags = static_cast<std::uint8_t>(f.flags | kRemote);
  }
  if (is_fd) {
    f.flags = static_cast<std::uint8_t>(f.flags | kFd | ((raw.flags & CANFD_BRS) ? kFdBrs : 0) |
                                        ((raw.flags & CANFD_ESI) ? kFdEsi : 0) |
                                        ((raw.flags & kCanFdFdf) ? kFdFdf : 0));
    ++stats_.fd_frames;
  }
  ++stats_.frames;
  *frame = f;
  return ReadStatus::kFrame;
}

}  // namespace vmass::can
