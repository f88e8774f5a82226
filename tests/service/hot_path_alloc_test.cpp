// The daemon's hot paths allocate nothing after start-up:
// - the estimator thread: given the simulated drive's CAN frames already read (the receive
//   thread's side), when the estimator side folds them into the SignalTable (InputSource::apply)
//   and ticks the pipeline (TickStep::tick) for the whole drive, then operator new is not called
//   once after the first second;
// - the receive thread on a live bus: given the drive's frames arriving as SocketCAN records on
//   the reader's file-descriptor seam (a socketpair, kernel time stamps on), when the receive
//   thread's loop reads them (SocketCanReader in batches, CanInputSource::next_record,
//   copy_record) and pushes them into the input ring, then operator new is not called once
//   after the first thousand frames.
//
// Counted with a replaced global operator new; AddressSanitizer and ThreadSanitizer bring their
// own, so under them the count is not taken (the test is skipped).
#include <linux/can.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <new>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "allocation_counter.hpp"
#include "vmass/config/config.hpp"
#include "vmass/runtime/can_input_source.hpp"
#include "vmass/runtime/candump_frame_source.hpp"
#include "vmass/runtime/socketcan_frame_source.hpp"
#include "vmass/runtime/spsc_queue.hpp"
#include "vmass/runtime/tick_step.hpp"
#include "vmass/signals/signal_mapping.hpp"

namespace vmass::service {
namespace {

using runtime::CandumpFrameSource;
using runtime::CanInputSource;
using runtime::InputRecord;
using runtime::InputSource;
using runtime::SpscQueue;
using runtime::TickStep;

namespace fs = std::filesystem;

/// The simulated paper_exp2 drive (config.yaml, drive.log, its DBC) in a fresh folder.
fs::path simulate_drive(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / (name + std::to_string(::getpid()));
  fs::remove_all(dir);
  const int status = std::system(
      (std::string(VMASS_SIM_BIN) + " --scenario paper_exp2 --out " + dir.string() + " > /dev/null")
          .c_str());
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  return dir;
}

TEST(HotPath, EstimatorSideOfTheCanInputAllocatesNothing) {
  if (!testing::counting_allocations())
    GTEST_SKIP() << "allocation counting is off under sanitizers";
  const fs::path dir = simulate_drive("vmass_hot_path_");
  ASSERT_FALSE(HasFailure());
  ConfigLoad config = load_config((dir / "config.yaml").string());
  ASSERT_TRUE(config.ok()) << config.error;
  signals::CanInputsLoad can = signals::load_can_inputs(*config.config);
  ASSERT_TRUE(can.ok()) << can.error;
  std::string error;
  auto frames = CandumpFrameSource::open((dir / "drive.log").string(), &error);
  ASSERT_TRUE(frames) << error;
  CanInputSource source(std::move(frames), can.inputs->decoder, can.inputs->mapping);
  // The receive thread's side (may allocate: file reading).
  std::vector<InputRecord> records;
  while (source.next_record(0) == InputSource::Read::kRecord) {
    records.emplace_back();
    source.copy_record(&records.back());
  }
  ASSERT_GT(records.size(), 100'000u);

  // The estimator thread's side: apply the records stamped <= T_k, then tick k.
  TickStep loop(config.config->pipeline);
  const TimeUs t0 = records.front().time_us;
  std::size_t next = 0;
  long after_first_second = -1;
  std::int64_t k = 0;
  for (; next < records.size(); ++k) {
    const TimeUs t = t0 + k * 10'000;
    while (next < records.size() && records[next].time_us <= t) source.apply(records[next++]);
    loop.tick(k, t, source);
    if (k == 100) after_first_second = testing::allocations();
  }
  ASSERT_GT(after_first_second, 1000) << "the counter does not count (set-up allocates)";
  const long allocations = testing::allocations() - after_first_second;
  EXPECT_GT(k, 19'000);
  EXPECT_TRUE(loop.last().estimate.mass_known);
  EXPECT_GT(loop.last().estimate.pairs_used, 500);
  EXPECT_EQ(allocations, 0) << "operator new calls in " << k - 100 << " ticks";
  fs::remove_all(dir);
}

/// The drive's frames as SocketCAN records (struct can_frame), as a CAN_RAW socket delivers them.
std::vector<can_frame> drive_records(const fs::path& log) {
  std::string error;
  auto frames = CandumpFrameSource::open(log.string(), &error);
  EXPECT_TRUE(frames) << error;
  std::vector<can_frame> records;
  can::CanFrame f;
  while (frames && frames->read(&f, 0) == runtime::FrameSource::Read::kFrame) {
    if (f.fd()) continue;  // classic frames: struct can_frame
    can_frame raw{};
    raw.can_id = f.id | (f.extended() ? CAN_EFF_FLAG : 0u);
    raw.len = f.len;
    std::copy(f.data, f.data + f.len, raw.data);
    records.push_back(raw);
  }
  return records;
}

TEST(HotPath, ReceiveSideOfTheSocketCanInputAllocatesNothing) {
  if (!testing::counting_allocations())
    GTEST_SKIP() << "allocation counting is off under sanitizers";
  const fs::path dir = simulate_drive("vmass_hot_path_receive_");
  ASSERT_FALSE(HasFailure());
  ConfigLoad config = load_config((dir / "config.yaml").string());
  ASSERT_TRUE(config.ok()) << config.error;
  signals::CanInputsLoad can = signals::load_can_inputs(*config.config);
  ASSERT_TRUE(can.ok()) << can.error;
  const std::vector<can_frame> records = drive_records(dir / "drive.log");
  ASSERT_GT(records.size(), 100'000u);
  int fds[2];
  ASSERT_EQ(::socketpair(AF_UNIX, SOCK_SEQPACKET, 0, fds), 0);
  const int one = 1;  // kernel time stamps, as on a CAN socket: control messages parsed too
  ASSERT_EQ(::setsockopt(fds[0], SOL_SOCKET, SO_TIMESTAMP, &one, sizeof one), 0);
  CanInputSource source(std::make_unique<runtime::SocketCanFrameSource>(
                            std::make_unique<can::SocketCanReader>(fds[0], nullptr), "pair"),
                        can.inputs->decoder, can.inputs->mapping);
  SpscQueue<InputRecord> ring(4096);
  InputRecord record;
  InputRecord popped;
  long after_warm_up = -1;
  std::size_t received = 0;
  constexpr std::size_t kChunk = 100;  // sent at once: the reader takes them in batches
  for (std::size_t sent = 0; sent < records.size();) {
    const std::size_t n = std::min(kChunk, records.size() - sent);
    for (std::size_t i = 0; i < n; ++i, ++sent) {
      ASSERT_EQ(::send(fds[1], &records[sent], sizeof(can_frame), 0),
                static_cast<ssize_t>(sizeof(can_frame)));
    }
    for (std::size_t i = 0; i < n; ++i, ++received) {  // the receive thread's loop
      ASSERT_EQ(source.next_record(1000), InputSource::Read::kRecord) << "record " << received;
      source.copy_record(&record);
      ASSERT_TRUE(ring.push(record));
      ASSERT_TRUE(ring.pop(&popped));  // the estimator's side, to keep room
    }
    if (after_warm_up < 0 && received >= 1000) after_warm_up = testing::allocations();
  }
  ASSERT_GT(after_warm_up, 1000) << "the counter does not count (set-up allocates)";
  const long allocations = testing::allocations() - after_warm_up;
  EXPECT_EQ(popped.frame.id, records.back().can_id & CAN_EFF_MASK);
  EXPECT_EQ(source.next_record(0), InputSource::Read::kTimeout);
  EXPECT_EQ(allocations, 0) << "operator new calls while receiving " << received - 1000
                            << " frames";
  ::close(fds[1]);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace vmass::service
