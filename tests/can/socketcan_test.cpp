// SocketCanReader through its file-descriptor seam: socketpair(AF_UNIX, SOCK_SEQPACKET) carrying
// struct can_frame / canfd_frame records, as a CAN_RAW socket delivers them.
#include <gtest/gtest.h>
#include <linux/can.h>
#include <linux/can/error.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <memory>

#include "vmass/can/socketcan.hpp"

namespace vmass::can {
namespace {

struct Pair {
  int reader = -1;
  int writer = -1;
  Pair() {
    int fds[2];
    if (::socketpair(AF_UNIX, SOCK_SEQPACKET, 0, fds) == 0) {
      reader = fds[0];
      writer = fds[1];
    }
  }
  ~Pair() {
    if (writer >= 0) ::close(writer);
  }
  void send_classic(canid_t id, std::initializer_list<std::uint8_t> bytes) const {
    can_frame f{};
    f.can_id = id;
    f.can_dlc = static_cast<std::uint8_t>(bytes.size());
    std::copy(bytes.begin(), bytes.end(), f.data);
    ASSERT_EQ(::send(writer, &f, sizeof f, 0), static_cast<ssize_t>(sizeof f));
  }
  void send_fd(canid_t id, std::uint8_t len, std::uint8_t flags) const {
    canfd_frame f{};
    f.can_id = id;
    f.len = len;
    f.flags = flags;
    for (int i = 0; i < len; ++i) f.data[i] = static_cast<std::uint8_t>(i + 1);
    ASSERT_EQ(::send(writer, &f, sizeof f, 0), static_cast<ssize_t>(sizeof f));
  }
};

TEST(SocketCan, ReadsClassicFdExtendedRemoteAndErrorRecords) {
  Pair p;
  ASSERT_GE(p.reader, 0);
  const int one = 1;
  ASSERT_EQ(::setsockopt(p.reader, SOL_SOCKET, SO_TIMESTAMP, &one, sizeof one), 0);
  SocketCanReader reader(p.reader, {});
  p.send_classic(0x123, {0xDE, 0xAD});
  p.send_classic(0x18DAF110 | CAN_EFF_FLAG, {1, 2, 3});
  p.send_classic(0x321 | CAN_RTR_FLAG, {});
  p.send_fd(0x7FF, 64, CANFD_BRS | 0x04 /* CANFD_FDF */);
  p.send_fd(0x1ABCDE | CAN_EFF_FLAG, 12, CANFD_ESI);
  p.send_classic(CAN_ERR_FLAG | CAN_ERR_BUSOFF | CAN_ERR_RESTARTED, {0, 0, 0, 0, 0, 0, 0, 0});
  p.send_classic(CAN_ERR_FLAG | CAN_ERR_CRTL, {0, 4, 0, 0, 0, 0, 0, 0});

  CanFrame f;
  ASSERT_EQ(reader.read(&f, 1000), ReadStatus::kFrame);
  EXPECT_EQ(f.id, 0x123u);
  EXPECT_EQ(f.flags, 0);
  EXPECT_EQ(f.len, 2);
  EXPECT_EQ(f.data[1], 0xAD);
  const std::int64_t t0 = f.time_us;
  EXPECT_GT(t0, 0);

  ASSERT_EQ(reader.read(&f, 1000), ReadStatus::kFrame);
  EXPECT_EQ(f.id, 0x18DAF110u);
  EXPECT_EQ(f.flags, kExtended);
  EXPECT_EQ(f.len, 3);
  EXPECT_GE(f.time_us, t0);

  ASSERT_EQ(reader.read(&f, 1000), ReadStatus::kFrame);
  EXPECT_EQ(f.id, 0x321u);
  EXPECT_EQ(f.flags, kRemote);

  ASSERT_EQ(reader.read(&f, 1000), ReadStatus::kFrame);
  EXPECT_EQ(f.id, 0x7FFu);
  EXPECT_EQ(f.flags, kFd | kFdBrs | kFdFdf);
  EXPECT_EQ(f.len, 64);
  EXPECT_EQ(f.data[63], 64);

  ASSERT_EQ(reader.read(&f, 1000), ReadStatus::kFrame);
  EXPECT_EQ(f.id, 0x1ABCDEu);
  EXPECT_EQ(f.flags, kFd | kFdEsi | kExtended);
  EXPECT_EQ(f.len, 12);

  ASSERT_EQ(reader.read(&f, 1000), ReadStatus::kFrame);
  EXPECT_TRUE(f.error());
  EXPECT_EQ(f.id, static_cast<std::uint32_t>(CAN_ERR_BUSOFF | CAN_ERR_RESTARTED));
  ASSERT_EQ(reader.read(&f, 1000), ReadStatus::kFrame);
  EXPECT_TRUE(f.error());

  const SocketCanStats& s = reader.stats();
  EXPECT_EQ(s.frames, 7u);
  EXPECT_EQ(s.fd_frames, 2u);
  EXPECT_EQ(s.error_frames, 2u);
  EXPECT_EQ(s.bus_off, 1u);
  EXPECT_EQ(s.restarts, 1u);
  EXPECT_EQ(s.controller_problems, 1u);
  EXPECT_EQ(s.no_kernel_timestamp, 0u);  // SO_TIMESTAMP delivered the kernel's stamp

  EXPECT_EQ(reader.read(&f, 10), ReadStatus::kTimeout);
}

TEST(SocketCan, RecordsWaitingAreReadInBatchesInOrder) {
  Pair p;
  ASSERT_GE(p.reader, 0);
  const int one = 1;
  ASSERT_EQ(::setsockopt(p.reader, SOL_SOCKET, SO_TIMESTAMP, &one, sizeof one), 0);
  SocketCanReader reader(p.reader, {});
  CanFrame f;
  EXPECT_EQ(reader.read(&f, 0), ReadStatus::kTimeout);  // nothing waiting: at once
  for (std::uint8_t i = 0; i < 100; ++i) p.send_classic(0x100 + i, {i});  // > 3 batches
  for (std::uint8_t i = 0; i < 100; ++i) {
    ASSERT_EQ(reader.read(&f, 0), ReadStatus::kFrame) << "record " << int{i};
    EXPECT_EQ(f.id, 0x100u + i);
    ASSERT_EQ(f.len, 1);
    EXPECT_EQ(f.data[0], i);
  }
  EXPECT_EQ(reader.read(&f, 0), ReadStatus::kTimeout);
  EXPECT_EQ(reader.stats().frames, 100u);
  EXPECT_EQ(reader.stats().no_kernel_timestamp, 0u);  // every record of a batch has its stamp
  p.send_classic(0x7, {7});
  ASSERT_EQ(reader.read(&f, 1000), ReadStatus::kFrame);  // after a wait
  EXPECT_EQ(f.id, 0x7u);
}

TEST(SocketCan, WithoutKernelStampsFallsBackAndCounts) {
  Pair p;
  SocketCanReader reader(p.reader, {});
  p.send_classic(0x1, {1});
  CanFrame f;
  ASSERT_EQ(reader.read(&f, 1000), ReadStatus::kFrame);
  EXPECT_EQ(reader.stats().no_kernel_timestamp, 1u);
  EXPECT_GT(f.time_us, 0);
}

TEST(SocketCan, MalformedRecordsAreCountedAndSkipped) {
  Pair p;
  SocketCanReader reader(p.reader, {});
  const char junk[10] = {};
  ASSERT_EQ(::send(p.writer, junk, sizeof junk, 0), 10);
  p.send_classic(0x42, {7});
  CanFrame f;
  ASSERT_EQ(reader.read(&f, 1000), ReadStatus::kFrame);
  EXPECT_EQ(f.id, 0x42u);
  EXPECT_EQ(reader.stats().malformed, 1u);
  ::close(p.writer);
  p.writer = -1;
  EXPECT_EQ(reader.read(&f, 1000), ReadStatus::kClosed);
}

TEST(SocketCan, NetworkDownKeepsTheSocket) {
  Pair p;
  int calls = 0;
  auto recv = [&](int fd, msghdr* msg, int flags) -> long {
    if (++calls == 1) {
      errno = ENETDOWN;
      return -1;
    }
    return ::recvmsg(fd, msg, flags);
  };
  SocketCanReader reader(p.reader, {}, 1, 8, recv);
  p.send_classic(0x10, {1});
  CanFrame f;
  EXPECT_EQ(reader.read(&f, 1000), ReadStatus::kInterfaceDown);
  EXPECT_EQ(reader.fd(), p.reader);
  ASSERT_EQ(reader.read(&f, 1000), ReadStatus::kFrame);
  EXPECT_EQ(f.id, 0x10u);
  EXPECT_EQ(reader.stats().interface_down, 1u);
  EXPECT_EQ(reader.stats().reopen_attempts, 0u);
}

TEST(SocketCan, DeviceGoneRecreatesTheSocketWithBackoff) {
  auto first = std::make_unique<Pair>();
  Pair second;
  int opens = 0;
  SocketCanReader::Opener opener = [&](std::string* error) {
    if (++opens < 3) {
      *error = "vcan0: no such interface";
      return -1;
    }
    return second.reader;
  };
  bool gone_sent = false;
  auto recv = [&](int fd, msghdr* msg, int flags) -> long {
    if (fd == first->reader && !gone_sent) {
      gone_sent = true;
      errno = ENODEV;
      return -1;
    }
    return ::recvmsg(fd, msg, flags);
  };
  SocketCanReader reader(first->reader, opener, 1, 4, recv);
  first->send_classic(0x1, {1});
  CanFrame f;
  EXPECT_EQ(reader.read(&f, 1000), ReadStatus::kInterfaceGone);
  EXPECT_EQ(reader.fd(), -1);
  second.send_classic(0x2, {2});
  ReadStatus st = ReadStatus::kReopening;
  for (int i = 0; i < 100 && st != ReadStatus::kFrame; ++i) st = reader.read(&f, 50);
  ASSERT_EQ(st, ReadStatus::kFrame);
  EXPECT_EQ(f.id, 0x2u);
  EXPECT_EQ(reader.fd(), second.reader);
  second.reader = -1;  // owned by the reader now
  EXPECT_EQ(opens, 3);
  EXPECT_EQ(reader.stats().interface_gone, 1u);
  EXPECT_EQ(reader.stats().reopen_attempts, 3u);
  EXPECT_EQ(reader.stats().reopens, 1u);
  first->reader = -1;  // closed by the reader when the device vanished
}

TEST(SocketCan, WithoutOpenerAVanishedDeviceStaysClosed) {
  Pair p;
  auto recv = [&](int, msghdr*, int) -> long {
    errno = ENODEV;
    return -1;
  };
  SocketCanReader reader(p.reader, {}, 1, 4, recv);
  p.send_classic(0x1, {1});
  CanFrame f;
  EXPECT_EQ(reader.read(&f, 100), ReadStatus::kInterfaceGone);
  EXPECT_EQ(reader.read(&f, 5), ReadStatus::kReopening);
}

TEST(SocketCan, OverflowCounterIsAccumulated) {
  SocketCanReader reader(-1, {});
  can_frame raw{};
  raw.can_id = 0x5;
  raw.can_dlc = 0;
  alignas(cmsghdr) unsigned char control[CMSG_SPACE(sizeof(std::uint32_t))];
  msghdr msg{};
  msg.msg_control = control;
  msg.msg_controllen = sizeof control;
  cmsghdr* c = CMSG_FIRSTHDR(&msg);
  c->cmsg_level = SOL_SOCKET;
  c->cmsg_type = SO_RXQ_OVFL;
  c->cmsg_len = CMSG_LEN(sizeof(std::uint32_t));
  CanFrame f;
  for (std::uint32_t count : {5u, 5u, 8u}) {
    std::memcpy(CMSG_DATA(c), &count, sizeof count);
    ASSERT_EQ(reader.handle_record(&raw, sizeof raw, &msg, &f), ReadStatus::kFrame);
  }
  EXPECT_EQ(reader.stats().dropped, 8u);
}

TEST(SocketCan, OpeningWithoutSocketCanIsAClearError) {
  SocketCanOptions opt;
  opt.interface = "vmassnone0";
  std::string error;
  const auto reader = SocketCanReader::open(opt, &error);
  EXPECT_EQ(reader, nullptr);
  EXPECT_NE(error.find("vmassnone0: "), std::string::npos) << error;
  const int probe = ::socket(PF_CAN, SOCK_RAW, CAN_RAW);
  if (probe < 0 && errno == EAFNOSUPPORT) {
    EXPECT_NE(error.find("this kernel has no SocketCAN"), std::string::npos) << error;
  } else {
    if (probe >= 0) ::close(probe);
    EXPECT_NE(error.find("no such interface"), std::string::npos) << error;
  }
}

TEST(SocketCan, OptionsValidateAndFiltersFromDbc) {
  SocketCanOptions opt;
  EXPECT_EQ(opt.validate(), "");
  opt.interface = "";
  EXPECT_NE(opt.validate().find("interface"), std::string::npos);
  opt.interface = "can0";
  opt.reopen_max_ms = 1;
  EXPECT_NE(opt.validate().find("reopen_max_ms"), std::string::npos);
  opt.reopen_max_ms = 5000;
  opt.filters.push_back({0x800, false});
  EXPECT_NE(opt.validate().find("filters"), std::string::npos);

  const DbcParseResult r = parse_dbc("BO_ 256 A: 8 X\nBO_ 2147484672 B: 8 X\n", "f.dbc");
  const auto filters = filters_for(r.database);
  ASSERT_EQ(filters.size(), 2u);
  EXPECT_EQ(filters[0].id, 256u);
  EXPECT_FALSE(filters[0].extended);
  EXPECT_EQ(filters[1].id, 0x400u);
  EXPECT_TRUE(filters[1].extended);
}

}  // namespace
}  // namespace vmass::can
