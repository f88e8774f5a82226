// A recording dated before 1970 (a TRC whose $STARTTIME is, an ASC dated 1969, a samples CSV with
// negative times) replays as its twin dated after: no negative time is taken for "never" (the
// input tables' sentinel is signals::kNeverUs, the most negative microsecond). A drive of the
// simulator, shifted 30 years into the past, gives tick for tick the estimate of the original.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "vmass/config/config.hpp"
#include "vmass/core/pipeline.hpp"
#include "vmass/runtime/can_input_source.hpp"
#include "vmass/runtime/input_source.hpp"
#include "vmass/runtime/tick_driver.hpp"
#include "vmass/signals/signal_mapping.hpp"
#include "vmass/sim/population.hpp"
#include "vmass/sim/population_drive.hpp"
#include "vmass/sim/population_scenarios.hpp"

namespace vmass {
namespace {

namespace fs = std::filesystem;

/// The frames of a vector, as a recording.
class VectorFrameSource final : public runtime::FrameSource {
 public:
  explicit VectorFrameSource(std::vector<can::CanFrame> frames) : frames_(std::move(frames)) {}
  Read read(can::CanFrame* frame, int /*timeout_ms*/) override {
    if (next_ == frames_.size()) return Read::kEnd;
    *frame = frames_[next_++];
    return Read::kFrame;
  }
  bool recorded() const override { return true; }
  std::string describe() const override { return "vector"; }
  std::string problem() const override { return ""; }

 private:
  std::vector<can::CanFrame> frames_;
  std::size_t next_ = 0;
};

struct Drive {
  std::vector<can::CanFrame> frames;
  std::unique_ptr<Config> config;
  std::shared_ptr<const can::Decoder> decoder;
  signals::SignalMapping mapping;
};

Drive simulate(const std::string& vehicle_id, const std::string& scenario) {
  Drive drive;
  const fs::path dir = fs::temp_directory_path() / ("vmass_before_1970_" + vehicle_id + scenario);
  fs::create_directories(dir);
  sim::DrawnVehicle d;
  std::string error;
  EXPECT_TRUE(sim::parse_vehicle_id(vehicle_id, &d, &error)) << error;
  sim::PopulationRun run;
  EXPECT_EQ(sim::make_population_run(d, scenario, 1, sim::Realism::all(), &run), "");
  sim::DriveOutput recorded;
  EXPECT_EQ(
      sim::record_drive(sim::population_drive(d, run, sim::Knowledge::kKnownScale), &recorded), "");
  EXPECT_EQ(sim::write_drive_files(recorded, dir.string()), "");
  drive.frames = recorded.handover.frames;
  ConfigLoad config = load_config((dir / "config.yaml").string());
  EXPECT_TRUE(config.ok()) << config.error;
  if (config.ok()) {
    const signals::CanInputsLoad can = signals::load_can_inputs(*config.config);
    EXPECT_TRUE(can.ok()) << can.error;
    if (can.ok()) {
      drive.decoder = can.inputs->decoder;
      drive.mapping = can.inputs->mapping;
    }
    drive.config = std::make_unique<Config>(*config.config);
  }
  fs::remove_all(dir);
  return drive;
}

/// Every tick's estimate of the drive's frames shifted by shift_us.
std::vector<Estimate> replay(const Drive& drive, TimeUs shift_us) {
  std::vector<can::CanFrame> frames = drive.frames;
  for (can::CanFrame& f : frames) f.time_us += shift_us;
  runtime::CanInputSource source(std::make_unique<VectorFrameSource>(std::move(frames)),
                                 drive.decoder, drive.mapping);
  auto pipeline = std::make_unique<Pipeline>(drive.config->pipeline);
  std::vector<Estimate> out;
  runtime::UnpacedClock clock;
  runtime::TickDriver(source, drive.config->pipeline.estimator.differencing.tick_rate_hz)
      .run(clock, [&](std::int64_t, TimeUs t) {
        pipeline->step(source.sample_at(t));
        out.push_back(pipeline->estimate());
      });
  return out;
}

TEST(TimesBefore1970, ACanDriveThirtyYearsEarlierGivesTheSameEstimates) {
  const Drive drive = simulate("compact-2", "paper_exp2_eps1");
  ASSERT_TRUE(drive.config && drive.decoder);
  ASSERT_GT(drive.frames.size(), 1000u);
  constexpr TimeUs kThirtyYearsUs = 30LL * 365 * 86400 * kUsPerSecond;
  const TimeUs shift_us = -drive.frames.front().time_us - kThirtyYearsUs;  // 1940
  const std::vector<Estimate> now = replay(drive, 0);
  const std::vector<Estimate> then = replay(drive, shift_us);
  ASSERT_EQ(then.size(), now.size());
  std::size_t with_mass = 0;
  for (std::size_t k = 0; k < now.size(); ++k) {
    ASSERT_LT(then[k].time_us, 0);
    ASSERT_EQ(then[k].time_us - shift_us, now[k].time_us) << k;
    ASSERT_EQ(then[k].status, now[k].status) << "tick " << k << ": " << then[k].describe_reason();
    ASSERT_EQ(then[k].reason, now[k].reason) << "tick " << k;
    ASSERT_EQ(then[k].has_mass(), now[k].has_mass()) << k;
    if (now[k].has_mass()) {
      ++with_mass;
      ASSERT_EQ(then[k].mass_kg, now[k].mass_kg) << k;
    }
  }
  EXPECT_GT(with_mass, now.size() / 2);
}

TEST(TimesBefore1970, ASamplesTableAtNegativeTimesIsValid) {
  runtime::InputValues values;
  runtime::InputTimeouts timeouts;
  for (TimeUs& t : timeouts.timeout_us) t = 50'000;
  values.latest.set(Input::kSpeed, 10.0);
  EXPECT_FALSE(runtime::sample_at(values, -1'000'000, timeouts).has(Input::kSpeed));  // never
  for (TimeUs& t : values.input_time_us) t = -1'000'000;  // a row at -1 s
  EXPECT_TRUE(runtime::sample_at(values, -990'000, timeouts).has(Input::kSpeed));
  EXPECT_FALSE(runtime::sample_at(values, -900'000, timeouts).has(Input::kSpeed));  // stale
}

}  // namespace
}  // namespace vmass
