// The `can.e2e` section and the SignalTable's receive validity: configuration errors name the
// key; a frame failing its counter or checksum updates nothing; a message is invalid after N
// failures and valid after M good frames, and so are the inputs it feeds; a spoofer at ten
// times the rate gets its value in during the first cycle at most, and is counted; frames longer
// than the DBC says are counted. The DBC is the simulator's layout (byte 6 XOR checksum, byte 7
// counter).
#include <gtest/gtest.h>

#include <string>

#include "vmass/signals/message_protection.hpp"
#include "vmass/signals/signal_table.hpp"

namespace vmass::signals {
namespace {

const char* kDbc = R"(BO_ 400 ESC_Speed: 8 PCM
 SG_ VehicleSpeed : 7|16@0+ (0.0078125,0) [0|511.9921875] "km/h" VMASS
 SG_ ESC_Speed_Checksum : 55|8@0+ (1,0) [0|255] "" VMASS
 SG_ ESC_Speed_Counter : 59|4@0+ (1,0) [0|15] "" VMASS
 SG_ Signed : 47|8@0- (1,0) [0|0] "" VMASS
BO_ 401 Short: 6 PCM
 SG_ Torque : 7|16@0- (1,0) [0|0] "Nm" VMASS
BA_DEF_ BO_ "GenMsgCycleTime" INT 0 10000;
BA_ "GenMsgCycleTime" BO_ 400 10;
)";

const char* kProtection =
    "messages:\n"
    "  ESC_Speed: {counter: ESC_Speed_Counter, checksum: ESC_Speed_Checksum, algorithm: xor,\n"
    "              data_id: id_low_byte, bytes: [0, 5]}\n";

std::shared_ptr<const can::Decoder> decoder() {
  can::DbcParseResult r = can::parse_dbc(kDbc, "sim.dbc");
  EXPECT_TRUE(r.ok());
  return std::make_shared<const can::Decoder>(*can::Decoder::compile(std::move(r.database)));
}

std::string protection_error(const std::string& yaml) {
  MessageProtection p;
  return parse_message_protection(YAML::Load(yaml), "c.yaml", *decoder(), "sim.dbc", &p);
}

TEST(MessageProtectionConfig, TheSimulatorsSchemeIsExpressed) {
  MessageProtection p;
  ASSERT_EQ(parse_message_protection(YAML::Load(kProtection), "c.yaml", *decoder(), "sim.dbc", &p),
            "");
  ASSERT_EQ(p.messages.size(), 1u);
  const can::E2eProfile& e = p.messages[0].profile;
  EXPECT_TRUE(e.counter.valid());
  EXPECT_TRUE(e.checksum.valid());
  EXPECT_EQ(e.data_id, 400u & 0xFFu);
  EXPECT_EQ(e.covered_bytes, 0x3Fu);
  EXPECT_EQ(p.invalid_after, 5);
  EXPECT_EQ(p.valid_after, 2);
  // Without bytes: every byte but the checksum's (6).
  ASSERT_EQ(parse_message_protection(
                YAML::Load("messages: {ESC_Speed: {checksum: ESC_Speed_Checksum, algorithm: "
                           "crc8_sae_j1850, data_id: 0x1234}}"),
                "c.yaml", *decoder(), "sim.dbc", &p),
            "");
  EXPECT_EQ(p.messages[0].profile.covered_bytes, 0xBFu);
  EXPECT_EQ(p.messages[0].profile.data_id, 0x1234u);
}

TEST(MessageProtectionConfig, ErrorsNameTheKey) {
  EXPECT_EQ(protection_error("messages: {Nope: {counter: X}}"),
            "c.yaml:1: can.e2e.messages.Nope: no message 'Nope' in sim.dbc");
  EXPECT_EQ(protection_error("messages: {ESC_Speed: {counter: Nope}}"),
            "c.yaml:1: can.e2e.messages.ESC_Speed.counter: message ESC_Speed has no signal 'Nope'");
  EXPECT_EQ(protection_error("messages: {ESC_Speed: {counter: Signed}}"),
            "c.yaml:1: can.e2e.messages.ESC_Speed.counter: ESC_Speed.Signed must be an unsigned, "
            "unmultiplexed integer");
  EXPECT_EQ(protection_error("messages: {ESC_Speed: {max_counter_step: 2}}"),
            "c.yaml:1: can.e2e.messages.ESC_Speed: give a counter:, a checksum: or both");
  EXPECT_NE(
      protection_error("messages: {ESC_Speed: {checksum: ESC_Speed_Checksum, algorithm: md5}}")
          .find("can.e2e.messages.ESC_Speed.algorithm: unknown checksum 'md5' (known: "
                "crc8_sae_j1850, xor, additive"),
      std::string::npos);
  EXPECT_EQ(protection_error("messages: {ESC_Speed: {checksum: ESC_Speed_Counter, algorithm: "
                             "crc8_sae_j1850}}"),
            "c.yaml:1: can.e2e.messages.ESC_Speed.checksum: algorithm crc8_sae_j1850 needs a 8-bit "
            "checksum signal, this one has 4");
  EXPECT_EQ(protection_error("messages: {ESC_Speed: {counter: ESC_Speed_Counter, bytes: [3, 8]}}"),
            "c.yaml:1: can.e2e.messages.ESC_Speed.bytes: expected [first, last] with 0 <= first <= "
            "last < 8 (the bytes of ESC_Speed)");
  EXPECT_EQ(protection_error("messages: {ESC_Speed: {checksum: ESC_Speed_Checksum, algorithm: xor, "
                             "data_id: 0x10000}}"),
            "c.yaml:1: can.e2e.messages.ESC_Speed.data_id: expected a number 0..0xFFFF or "
            "id_low_byte, got '0x10000'");
  EXPECT_EQ(protection_error("invalid_after: 0"),
            "c.yaml:1: can.e2e.invalid_after: must be 1..1000");
}

class ProtectedTable : public ::testing::Test {
 protected:
  ProtectedTable() : decoder_(decoder()) {
    SignalMapping m;
    EXPECT_EQ(parse_signal_mapping(YAML::Load("speed: {message: ESC_Speed, signal: VehicleSpeed}\n"
                                              "wheel_torque: {message: Short, signal: Torque}"),
                                   "c.yaml", *decoder_, "sim.dbc", &m),
              "");
    EXPECT_EQ(parse_message_protection(YAML::Load(kProtection), "c.yaml", *decoder_, "sim.dbc",
                                       &m.protection),
              "");
    table_ = std::make_unique<SignalTable>(decoder_, m);
  }
  /// A frame of ESC_Speed as the simulator's `protect` writes it.
  static can::CanFrame frame(int counter, double kmh, TimeUs t) {
    can::CanFrame f;
    f.id = 400;
    f.len = 8;
    f.time_us = t;
    const auto raw = static_cast<int>(kmh / 0.0078125);
    f.data[0] = static_cast<std::uint8_t>(raw >> 8);
    f.data[1] = static_cast<std::uint8_t>(raw & 0xFF);
    f.data[7] = static_cast<std::uint8_t>(counter & 0x0F);
    std::uint8_t x = 400 & 0xFF;
    for (int b = 0; b < 6; ++b) x ^= f.data[b];
    f.data[6] = x;
    return f;
  }
  double speed_kmh(TimeUs t) {
    const Sample s = table_->sample_at(t);
    return s.has(Input::kSpeed) ? s.speed_mps * 3.6 : -1.0;
  }
  const MessageCounters& counters() const { return table_->message_counters(0); }

  std::shared_ptr<const can::Decoder> decoder_;
  std::unique_ptr<SignalTable> table_;
};

TEST_F(ProtectedTable, GoodFramesAreCommitted) {
  for (int j = 0; j < 50; ++j) table_->on_frame(frame(j, 50.0 + j, j * 10'000));
  EXPECT_NEAR(speed_kmh(490'000), 99.0, 0.01);
  EXPECT_EQ(counters().committed, 50u);
  EXPECT_EQ(counters().counter_fail + counters().checksum_fail + counters().too_fast, 0u);
  EXPECT_TRUE(table_->bus_valid());
}

TEST_F(ProtectedTable, AFailedFrameUpdatesNothing) {
  table_->on_frame(frame(0, 50.0, 0));
  can::CanFrame flipped = frame(1, 50.0, 10'000);
  flipped.data[0] ^= 0x20;  // +64 km/h, in range: only the checksum sees it
  table_->on_frame(flipped);
  EXPECT_NEAR(speed_kmh(10'000), 50.0, 0.01);
  EXPECT_EQ(counters().checksum_fail, 1u);
  EXPECT_EQ(table_->counters().inputs[static_cast<int>(Input::kSpeed)].checksum_fail, 1u);
  table_->on_frame(frame(1, 50.0, 10'000));  // a replay of the frame before it
  table_->on_frame(frame(1, 51.0, 20'000));  // frozen counter
  EXPECT_NEAR(speed_kmh(20'000), 50.0, 0.01);
  EXPECT_EQ(counters().counter_fail, 1u);
}

TEST_F(ProtectedTable, InvalidAfterFiveFailuresValidAfterTwoGoodFrames) {
  table_->on_frame(frame(0, 50.0, 0));
  for (int j = 1; j <= 5; ++j) table_->on_frame(frame(0, 60.0, j * 10'000));  // frozen frame
  EXPECT_FALSE(table_->message_valid(0));
  EXPECT_FALSE(table_->bus_valid());
  EXPECT_EQ(speed_kmh(50'000), -1.0);
  EXPECT_EQ(table_->verdict(Input::kSpeed).fault, InputFault::kMessageInvalid);
  EXPECT_EQ(table_->verdict(Input::kSpeed).message, 0);
  table_->on_frame(frame(1, 70.0, 60'000));  // good, withheld
  EXPECT_EQ(speed_kmh(60'000), -1.0);
  table_->on_frame(frame(2, 71.0, 70'000));  // the second good frame: valid, committed
  EXPECT_NEAR(speed_kmh(70'000), 71.0, 0.01);
  EXPECT_TRUE(table_->bus_valid());
  EXPECT_EQ(counters().withheld, 1u);
}

TEST_F(ProtectedTable, ASpooferAtTenTimesTheRateIsShutOut) {
  TimeUs t = 0;
  int counter = 0;
  for (int j = 0; j < 300; ++j, t += 10'000) {
    table_->on_frame(frame(counter++, 80.0, t));  // the real ECU
    for (int k = 1; k < 10; ++k) {                // nine spoofed frames: speed 0, valid checksum,
      table_->on_frame(frame(counter + k, 0.0, t + k * 1'000));  // a guessed counter
    }
    const double kmh = speed_kmh(t + 9'000);
    // The bucket's burst lets the first spoofed frames of the first cycle in, then never
    // again (and the plausibility checks refuse such a jump anyway).
    if (j > 0) {
      ASSERT_TRUE(kmh < 0.0 || std::abs(kmh - 80.0) < 0.01) << j << ": " << kmh;
    }
  }
  EXPECT_FALSE(table_->message_valid(0));
  EXPECT_GT(counters().too_fast, 2000u);
  // Each cycle two counters jump (the real frame's, the first spoofed one's); the spoofed frames'
  // own sequence steps by one: the rate, not the counter, shuts them out.
  EXPECT_GE(counters().counter_fail, 598u);
}

TEST_F(ProtectedTable, FramesLongerThanTheDbcSaysAreCounted) {
  can::CanFrame f;
  f.id = 401;
  f.len = 8;  // the DBC says 6
  table_->on_frame(f, 0);
  const int slot = table_->watched_message(0) == 1 ? 0 : 1;
  EXPECT_EQ(table_->message_counters(slot).too_long, 1u);
}

}  // namespace
}  // namespace vmass::signals
