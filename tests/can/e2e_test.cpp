// End-to-end protection (can/checksum.hpp, can/e2e.hpp): the checksums against published check
// values and hand computations, the alive counter against frozen, replayed and interleaved
// streams, and the message validity state machine (invalid after N failures, valid after M good
// frames).
#include "vmass/can/e2e.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "vmass/can/dbc.hpp"

namespace vmass::can {
namespace {

/// The bytes of `text` (which must outlive the input).
ChecksumInput bytes_of(const std::string& text, int bits = 8) {
  ChecksumInput in;
  in.bytes = reinterpret_cast<const std::uint8_t*>(text.data());
  in.size = text.size();
  in.bits = bits;
  return in;
}

TEST(Checksum, Crc8SaeJ1850MatchesItsCheckValue) {
  // The catalogue's check value of CRC-8/SAE-J1850 over "123456789", and AUTOSAR's examples
  // (Crc_CalculateCRC8: 00 00 00 00 -> 0x59, F2 01 83 -> 0x37).
  const std::string check = "123456789", zeros(4, '\0'), autosar = "\xF2\x01\x83";
  EXPECT_EQ(crc8_sae_j1850(bytes_of(check)), 0x4Bu);
  EXPECT_EQ(crc8_sae_j1850(bytes_of(zeros)), 0x59u);
  EXPECT_EQ(crc8_sae_j1850(bytes_of(autosar)), 0x37u);
  // A data id goes first: the same as its bytes prepended to the data.
  const std::string data = "\x10\x20", prepended = "\x34\x12\x10\x20";
  ChecksumInput with_id = bytes_of(data);
  with_id.has_data_id = true;
  with_id.data_id = 0x1234;
  EXPECT_EQ(crc8_sae_j1850(with_id), crc8_sae_j1850(bytes_of(prepended)));
}

TEST(Checksum, XorAndAdditiveByHand) {
  const std::string data = "\x01\x02\x04\xF0";
  ChecksumInput in = bytes_of(data);
  EXPECT_EQ(xor_checksum(in), 0xF7u);
  EXPECT_EQ(additive_checksum(in), 0xF7u);
  in.has_data_id = true;
  in.data_id = 0x80;
  EXPECT_EQ(xor_checksum(in), 0x77u);
  EXPECT_EQ(additive_checksum(in), (0x80u + 0xF7u) & 0xFFu);
  in.bits = 4;  // a nibble: 0x77 folded = 7 ^ 7, the sum's low nibble
  EXPECT_EQ(xor_checksum(in), 0x0u);
  EXPECT_EQ(additive_checksum(in), (0x80u + 0xF7u) & 0xFu);
}

std::uint64_t ones(const ChecksumInput&) { return 1; }

TEST(Checksum, AVehiclesOwnAlgorithmIsRegisteredByName) {
  EXPECT_NE(find_checksum("crc8_sae_j1850"), nullptr);
  EXPECT_EQ(find_checksum("acme_ones"), nullptr);
  EXPECT_TRUE(register_checksum({"acme_ones", &ones, "always 1", 0}));
  EXPECT_FALSE(register_checksum({"acme_ones", &ones, "twice", 0}));  // a name is taken once
  ASSERT_NE(find_checksum("acme_ones"), nullptr);
  const std::string x = "x";
  EXPECT_EQ(find_checksum("acme_ones")->compute(bytes_of(x)), 1u);
  EXPECT_NE(checksum_names().find("acme_ones"), std::string::npos);
}

// vmass-sim's protected message: counter in byte 7's low nibble (Motorola 59|4), checksum in
// byte 6 (55|8) = XOR of the id's low byte and bytes 0..5.
const char* kSimDbc = R"(BO_ 400 ESC_Speed: 8 PCM
 SG_ VehicleSpeed : 7|16@0+ (0.0078125,0) [0|511.9921875] "km/h" VMASS
 SG_ ESC_Speed_Checksum : 55|8@0+ (1,0) [0|255] "" VMASS
 SG_ ESC_Speed_Counter : 59|4@0+ (1,0) [0|15] "" VMASS
)";

class E2eTest : public ::testing::Test {
 protected:
  E2eTest() {
    DbcParseResult r = parse_dbc(kSimDbc, "sim.dbc");
    decoder_ = *Decoder::compile(std::move(r.database));
    profile_.counter = decoder_->find_signal("ESC_Speed", "ESC_Speed_Counter");
    profile_.checksum = decoder_->find_signal("ESC_Speed", "ESC_Speed_Checksum");
    profile_.algorithm = &xor_checksum;
    profile_.has_data_id = true;
    profile_.data_id = 400 & 0xFF;
    profile_.covered_bytes = 0x3F;  // bytes 0..5
  }
  /// A frame as the simulator's `protect` writes it.
  CanFrame frame(int counter, int speed_raw) const {
    CanFrame f;
    f.id = 400;
    f.len = 8;
    f.data[0] = static_cast<std::uint8_t>(speed_raw >> 8);
    f.data[1] = static_cast<std::uint8_t>(speed_raw & 0xFF);
    f.data[7] = static_cast<std::uint8_t>(counter & 0x0F);
    std::uint8_t x = 400 & 0xFF;
    for (int b = 0; b < 6; ++b) x ^= f.data[b];
    f.data[6] = x;
    return f;
  }
  E2eResult check(const CanFrame& f, bool resync = false) {
    return check_e2e(*decoder_, profile_, f, resync, &state_);
  }
  std::optional<Decoder> decoder_;
  E2eProfile profile_;
  E2eState state_;
};

TEST_F(E2eTest, TheSimulatorsProtectionPasses) {
  for (int j = 0; j < 40; ++j) EXPECT_EQ(check(frame(j, 1000 + j)), E2eResult::kOk) << j;
}

TEST_F(E2eTest, ABadChecksumFailsWhateverTheCounter) {
  EXPECT_EQ(check(frame(0, 1000)), E2eResult::kOk);
  CanFrame f = frame(1, 1000);
  f.data[1] ^= 0x04;  // a bit flip in the speed
  EXPECT_EQ(check(f), E2eResult::kChecksumFail);
  CanFrame spoof = frame(2, 0);
  spoof.data[6] ^= 0xFF;  // the spoofer does not know the scheme
  EXPECT_EQ(check(spoof), E2eResult::kChecksumFail);
}

TEST_F(E2eTest, FrozenReplayedAndInterleavedCountersFail) {
  EXPECT_EQ(check(frame(14, 1000)), E2eResult::kOk);
  EXPECT_EQ(check(frame(15, 1000)), E2eResult::kOk);
  EXPECT_EQ(check(frame(0, 1000)), E2eResult::kOk);           // wraps at 2^4
  EXPECT_EQ(check(frame(0, 1000)), E2eResult::kCounterFail);  // frozen: the counter repeats
  EXPECT_EQ(check(frame(1, 1000)), E2eResult::kOk);
  EXPECT_EQ(check(frame(9, 1000)), E2eResult::kCounterFail);  // replayed from elsewhere
  EXPECT_EQ(check(frame(10, 1000)), E2eResult::kOk);          // one bad frame costs one frame
  // A spoofer sending valid frames between the real ones: every frame steps by 0 or 2.
  int good = 0;
  for (int j = 11; j < 31; ++j) {
    good += check(frame(j, 1000)) == E2eResult::kOk;   // real
    good += check(frame(j + 5, 0)) == E2eResult::kOk;  // spoofed, its own counter
  }
  EXPECT_EQ(good, 1);  // the first real frame, before the spoofer's first
}

TEST_F(E2eTest, AGapRestartsTheCounter) {
  EXPECT_EQ(check(frame(3, 1000)), E2eResult::kOk);
  EXPECT_EQ(check(frame(11, 1000), /*resync=*/true), E2eResult::kOk);
  EXPECT_EQ(check(frame(12, 1000)), E2eResult::kOk);
}

TEST_F(E2eTest, AllowedStepsAboveOne) {
  profile_.max_counter_step = 2;  // a receiver that may miss one frame
  EXPECT_EQ(check(frame(0, 1)), E2eResult::kOk);
  EXPECT_EQ(check(frame(2, 1)), E2eResult::kOk);
  EXPECT_EQ(check(frame(5, 1)), E2eResult::kCounterFail);
}

TEST(MessageValidity, InvalidAfterNFailuresValidAfterMGoodFrames) {
  MessageValidity v(3, 2);
  EXPECT_FALSE(v.on_frame(false));  // a failed frame is never committed
  EXPECT_FALSE(v.on_frame(false));
  EXPECT_TRUE(v.valid());         // two in a row: still valid
  EXPECT_TRUE(v.on_frame(true));  // a good frame resets the run of failures
  for (int i = 0; i < 3; ++i) v.on_frame(false);
  EXPECT_FALSE(v.valid());
  EXPECT_FALSE(v.on_frame(true));  // good, but the message is invalid: withheld
  EXPECT_FALSE(v.on_frame(false));
  EXPECT_FALSE(v.on_frame(true));
  EXPECT_TRUE(v.on_frame(true));  // the second good frame in a row: valid, committed
  EXPECT_TRUE(v.valid());
}

}  // namespace
}  // namespace vmass::can
