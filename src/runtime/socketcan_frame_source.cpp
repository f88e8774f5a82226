#include "vmass/runtime/socketcan_frame_source.hpp"

#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>

#include <linux/can.h>

namespace vmass::runtime {

std::unique_ptr<SocketCanFrameSource> SocketCanFrameSource::open(
    const can::SocketCanOptions& options, std::string* error) {
  std::string why;
  int fd = can::open_can_socket(options, &why);
  if (fd < 0) {
    // Tell "this kernel has no CAN" (fatal) from "the interface is not there yet" (wait).
    const int probe = ::socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
    if (probe < 0 && (errno == EAFNOSUPPORT || errno == EPROTONOSUPPORT)) {
      if (error) *error = options.interface + ": " + why;
      return nullptr;
    }
    if (probe >= 0) ::close(probe);
  }
  auto reader = std::make_unique<can::SocketCanReader>(
      fd, [options](std::string* e) { return can::open_can_socket(options, e); },
      options.reopen_initial_ms, options.reopen_max_ms);
  return std::make_unique<SocketCanFrameSource>(std::move(reader), options.interface);
}

SocketCanFrameSource::SocketCanFrameSource(std::unique_ptr<can::SocketCanReader> reader,
                                           std::string interface)
    : reader_(std::move(reader)), interface_(std::move(interface)) {}

FrameSource::Read SocketCanFrameSource::read(can::CanFrame* frame, int timeout_ms) {
  switch (reader_->read(frame, timeout_ms)) {
    case can::ReadStatus::kFrame:
      return Read::kFrame;
    case can::ReadStatus::kTimeout:
    case can::ReadStatus::kError:  // socket kept; counted by the reader
      return Read::kTimeout;
    case can::ReadStatus::kInterfaceDown:
    case can::ReadStatus::kInterfaceGone:
    case can::ReadStatus::kReopening:
      return Read::kDown;
    case can::ReadStatus::kClosed:
      return Read::kEnd;
  }
  return Read::kTimeout;
}

}  // namespace vmass::runtime
