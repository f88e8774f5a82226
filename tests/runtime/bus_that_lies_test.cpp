// A bus that lies, end to end through the product's path (the DBC and can.inputs mapping a
// population vehicle's engineer writes, plus the can.e2e section that declares the simulator's
// protection, a CanInputSource, the tick driver): the simulator's sensor_faults drive has each
// planted fault seen in its own window (a missing message stale, a frozen steering sensor stuck,
// absurd values beyond their limits, unknown and malformed frames counted) and nothing flagged
// anywhere else; on a clean drive, frozen, replayed and spoofed frames are refused by the E2E
// checks and the spoofed speed never reaches a sample.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "vmass/can/candump.hpp"
#include "vmass/config/config.hpp"
#include "vmass/runtime/can_input_source.hpp"
#include "vmass/runtime/candump_frame_source.hpp"
#include "vmass/runtime/tick_driver.hpp"
#include "vmass/signals/signal_mapping.hpp"
#include "vmass/sim/population.hpp"
#include "vmass/sim/population_drive.hpp"
#include "vmass/sim/population_scenarios.hpp"

namespace vmass {
namespace {

namespace fs = std::filesystem;

/// A simulated population run: its DBC and mapping, and its frames.
struct Bus {
  std::string dbc_text;
  std::string inputs_yaml;  ///< the can.inputs the vehicle's engineer wrote (known inputs only)
  std::string e2e_yaml;     ///< can.e2e declaring the simulator's protection
  std::vector<can::CanFrame> frames;
};

Bus simulate(const std::string& vehicle_id, const std::string& scenario, const fs::path& dir) {
  Bus bus;
  sim::DrawnVehicle d;
  std::string error;
  EXPECT_TRUE(sim::parse_vehicle_id(vehicle_id, &d, &error)) << error;
  sim::PopulationRun run;
  EXPECT_EQ(sim::make_population_run(d, scenario, 1, sim::Realism::all(), &run), "");
  sim::DriveOutput drive;
  EXPECT_EQ(sim::record_drive(sim::population_drive(d, run, sim::Knowledge::kKnownScale), &drive),
            "");
  EXPECT_EQ(sim::write_drive_files(drive, dir.string()), "");
  bus.frames = drive.handover.frames;
  std::ifstream dbc(dir / "vehicle.dbc");
  std::stringstream text;
  text << dbc.rdbuf();
  bus.dbc_text = text.str();
  // The engineer's mapping, less the inputs this estimator does not read yet.
  const YAML::Node inputs = YAML::LoadFile((dir / "config.yaml").string())["can"]["inputs"];
  YAML::Node kept(YAML::NodeType::Map);
  for (const auto& kv : inputs) {
    const std::string name = kv.first.as<std::string>();
    for (int i = 0; i < kInputCount; ++i) {
      if (name == input_name(static_cast<Input>(i))) kept[name] = kv.second;
    }
  }
  YAML::Emitter out;
  out << YAML::Flow << kept;
  bus.inputs_yaml = out.c_str();
  // can.e2e: every message with a counter, as the simulator's `protect` writes it.
  std::istringstream lines(bus.dbc_text);
  std::string line;
  bus.e2e_yaml = "{messages: {";
  bool first = true;
  while (std::getline(lines, line)) {
    const auto at = line.find("_Counter :");
    if (line.rfind(" SG_ ", 0) != 0 || at == std::string::npos) continue;
    const std::string m = line.substr(5, at - 5);
    bus.e2e_yaml += (first ? "" : ", ") + m + ": {counter: " + m + "_Counter, checksum: " + m +
                    "_Checksum, algorithm: xor, data_id: id_low_byte, bytes: [0, 5]}";
    first = false;
  }
  bus.e2e_yaml += "}}";
  return bus;
}

/// The CAN input of a bus's frames (possibly tampered with), through the real loaders.
std::unique_ptr<runtime::CanInputSource> input(const Bus& bus, const fs::path& dir,
                                               const std::vector<can::CanFrame>& frames) {
  std::ofstream(dir / "config.yaml") << "vehicle:\n  empty_mass_kg: 1500\n  wheelbase_m: 2.7\n"
                                        "  cg_to_front_axle_m: 1.2\n  wheel_radius_m: 0.31\n"
                                        "  brake_gain_n_per_pa: 0.0033\n  steering_ratio: 15\n"
                                        "  cornering_stiffness_front_n_per_rad: 150000\n"
                                        "  cornering_stiffness_rear_n_per_rad: 170000\n"
                                        "suspension:\n  stiffness_n_per_m: 30000\n"
                                        "can:\n  dbc: vehicle.dbc\n  e2e: "
                                     << bus.e2e_yaml << "\n  inputs: " << bus.inputs_yaml << "\n";
  const ConfigLoad config = load_config((dir / "config.yaml").string());
  EXPECT_TRUE(config.ok()) << config.error;
  const signals::CanInputsLoad can = signals::load_can_inputs(*config.config);
  EXPECT_TRUE(can.ok()) << can.error;
  std::string log;
  for (const can::CanFrame& f : frames) log += can::format_candump_line(f, "can0");
  return std::make_unique<runtime::CanInputSource>(
      runtime::CandumpFrameSource::from_text(std::move(log), "drive.log"), can.inputs->decoder,
      can.inputs->mapping);
}

struct Flag {
  double t_s;
  Input input;
  signals::InputFault fault;
};

/// Plays the input; every verdict of every tick, and the samples.
std::vector<Flag> play(runtime::CanInputSource& source, std::vector<Sample>* samples = nullptr) {
  std::vector<Flag> flags;
  runtime::UnpacedClock clock;
  TimeUs t0 = -1;
  runtime::TickDriver(source, 100.0).run(clock, [&](std::int64_t, TimeUs t) {
    if (t0 < 0) t0 = t;
    const Sample s = source.sample_at(t);
    if (samples) samples->push_back(s);
    runtime::InputHealthRecord h;
    source.health_record(&h);
    for (int i = 0; i < kInputCount; ++i) {
      const signals::InputFault f = h.inputs[static_cast<std::size_t>(i)].verdict.fault;
      if (f != signals::InputFault::kNone && f != signals::InputFault::kNotReceived) {
        flags.push_back({static_cast<double>(t - t0) * 1e-6, static_cast<Input>(i), f});
      }
    }
  });
  return flags;
}

class BusThatLies : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("vmass_bus_lies_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(BusThatLies, EveryPlantedSensorFaultIsSeenInItsWindowAndNothingElse) {
  // compact-11: wheel torque, deflection, lateral sensors; its faults (population_scenarios):
  // dynamics missing 40-43 s, steering frozen 60-70 s, speed absurd at 90 s, dynamics absurd
  // at 95 s, unknown frames 110-110.5 s, powertrain frames 2 bytes long 130-130.5 s.
  const Bus bus = simulate("compact-11", "sensor_faults", dir_);
  auto source = input(bus, dir_, bus.frames);
  const std::vector<Flag> flags = play(*source);
  auto seen = [&](Input in, signals::InputFault f, double from_s, double to_s) {
    return std::any_of(flags.begin(), flags.end(), [&](const Flag& x) {
      return x.input == in && x.fault == f && x.t_s >= from_s && x.t_s <= to_s;
    });
  };
  using F = signals::InputFault;
  EXPECT_TRUE(seen(Input::kYawRate, F::kStale, 40.0, 43.0));
  EXPECT_TRUE(seen(Input::kSteeringWheelAngle, F::kStuck, 60.0, 70.0));
  EXPECT_TRUE(seen(Input::kSpeed, F::kAboveMaximum, 90.0, 90.1));
  EXPECT_TRUE(seen(Input::kAccelX, F::kAboveMaximum, 95.0, 95.1));
  EXPECT_TRUE(seen(Input::kWheelTorque, F::kStale, 130.0, 130.6));
  for (const Flag& x : flags) {
    const bool expected = (x.t_s >= 40.0 && x.t_s <= 43.1) || (x.t_s >= 60.0 && x.t_s <= 70.1) ||
                          (x.t_s >= 90.0 && x.t_s <= 90.2) || (x.t_s >= 95.0 && x.t_s <= 95.2) ||
                          (x.t_s >= 130.0 && x.t_s <= 130.7);
    EXPECT_TRUE(expected) << x.t_s << " s: " << input_name(x.input) << " "
                          << signals::input_fault_name(x.fault);
  }
  const signals::SignalTableCounters& c = source->table().counters();
  EXPECT_GE(c.unknown_id, 900u);  // 2000 frames a second for 0.5 s
  EXPECT_GE(c.malformed, 20u);    // 2-byte powertrain frames: every 20 ms for 0.5 s
  for (int k = 0; k < source->table().watched_count(); ++k) {
    EXPECT_EQ(source->table().message_counters(k).counter_fail, 0u) << k;
    EXPECT_EQ(source->table().message_counters(k).checksum_fail, 0u) << k;
  }
}

TEST_F(BusThatLies, FrozenReplayedAndSpoofedFramesAreRefused) {
  const Bus bus = simulate("compact-11", "paper_exp2_eps1", dir_);
  const int speed_id = [&] {
    for (const can::CanFrame& f : bus.frames) {
      if (bus.dbc_text.find("BO_ " + std::to_string(f.id) + " ESC_Speed:") != std::string::npos) {
        return static_cast<int>(f.id);
      }
    }
    return -1;
  }();
  ASSERT_GT(speed_id, 0);
  std::vector<can::CanFrame> tampered;
  can::CanFrame frozen{};
  std::vector<can::CanFrame> old_speed;
  for (const can::CanFrame& f : bus.frames) {
    const double t = static_cast<double>(f.time_us) * 1e-6;
    const bool speed = static_cast<int>(f.id) == speed_id;
    if (speed && t < 50.0) old_speed.push_back(f);
    if (speed && t >= 60.0 && t < 62.0) {  // frozen: the same frame again and again
      if (frozen.len == 0) frozen = f;
      can::CanFrame again = frozen;
      again.time_us = f.time_us;
      tampered.push_back(again);
      continue;
    }
    if (speed && t >= 80.0 && t < 82.0) {  // replayed: frames from 40 s before, in place
      // The recorded frame of 40 s before (by time: the message's rate is the DBC's, not 100 Hz;
      // indexing as if it were read past the end, found by AddressSanitizer).
      const auto earlier = std::lower_bound(
          old_speed.begin(), old_speed.end(), f.time_us - 40'000'000,
          [](const can::CanFrame& o, std::int64_t time_us) { return o.time_us < time_us; });
      ASSERT_NE(earlier, old_speed.end());
      can::CanFrame replay = *earlier;
      replay.time_us = f.time_us;
      tampered.push_back(replay);
      continue;
    }
    tampered.push_back(f);
    if (speed && t >= 100.0 && t < 103.0) {  // spoofed: speed 0 nine times between real ones
      for (int k = 1; k < 10; ++k) {
        can::CanFrame spoof = f;
        spoof.data[0] = spoof.data[1] = 0;
        spoof.data[7] =
            static_cast<std::uint8_t>((spoof.data[7] & 0xF0) | ((f.data[7] + k) & 0x0F));
        std::uint8_t x = static_cast<std::uint8_t>(f.id & 0xFF);
        for (int b = 0; b < 6; ++b) x ^= spoof.data[b];
        spoof.data[6] = x;  // a spoofer who knows the checksum
        spoof.time_us = f.time_us + k * 1000;
        tampered.push_back(spoof);
      }
    }
  }
  auto source = input(bus, dir_, tampered);
  std::vector<Sample> samples;
  play(*source, &samples);
  int spoofed_through = 0;
  for (std::size_t k = 10000; k < 10300 && k < samples.size(); ++k) {
    spoofed_through += samples[k].has(Input::kSpeed) && samples[k].speed_mps < 0.5;
  }
  EXPECT_EQ(spoofed_through, 0);
  const int slot = [&] {
    for (int k = 0; k < source->table().watched_count(); ++k) {
      if (source->message_name(source->table().watched_message(k)) == "ESC_Speed") return k;
    }
    return -1;
  }();
  ASSERT_GE(slot, 0);
  const signals::MessageCounters& m = source->table().message_counters(slot);
  EXPECT_GE(m.counter_fail, 150u);  // the frozen frame's 200 repeats (and the replay's jumps)
  EXPECT_GE(m.too_fast, 1000u);     // most of the 9 spoofed frames a cycle (20 ms), for 3 s
  EXPECT_TRUE(source->table().message_valid(slot));  // valid again after the attacks
  EXPECT_TRUE(samples.back().has(Input::kSpeed));
}

}  // namespace
}  // namespace vmass
