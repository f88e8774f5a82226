// The estimator thread's hot path allocates nothing after start-up: given the simulated drive's
// CAN frames already read (the receive thread's side), when the estimator side folds them into
// the SignalTable (InputSource::apply) and ticks the pipeline (TickStep::tick) for the whole
// drive, then operator new is not called once after the first second.
//
// Counted with a replaced global operator new; AddressSanitizer and ThreadSanitizer bring their
// own, so under them the count is not taken (the test is skipped).
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
#include "vmass/runtime/tick_step.hpp"
#include "vmass/signals/signal_mapping.hpp"

namespace vmass::service {
namespace {

using runtime::CandumpFrameSource;
using runtime::CanInputSource;
using runtime::InputRecord;
using runtime::InputSource;
using runtime::TickStep;

namespace fs = std::filesystem;

TEST(HotPath, EstimatorSideOfTheCanInputAllocatesNothing) {
  if (!testing::counting_allocations())
    GTEST_SKIP() << "allocation counting is off under sanitizers";
  const fs::path dir = fs::temp_directory_path() / ("vmass_hot_path_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const int status = std::system(
      (std::string(VMASS_SIM_BIN) + " --scenario paper_exp2 --out " + dir.string() + " > /dev/null")
          .c_str());
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
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

}  // namespace
}  // namespace vmass::service
