// decode()'s frame-word path (messages of at most 8 bytes: one little- and one big-endian read
// of the payload, three shifts per signal) against an independent bit walk and against the
// per-signal path (signal_value), on random layouts of every classic length with garbage after
// the payload; and the extended-id hash table against a plain search.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <set>
#include <string>

#include "bit_walk.hpp"
#include "vmass/can/decoder.hpp"

namespace vmass::can {
namespace {

Decoder compile_text(const std::string& text) {
  DbcParseResult r = parse_dbc(text, "test.dbc");
  EXPECT_TRUE(r.ok());
  std::string err;
  auto d = Decoder::compile(std::move(r.database), &err);
  EXPECT_TRUE(d.has_value()) << err;
  return std::move(*d);
}

TEST(DecoderWordPath, EveryClassicLengthMatchesTheWalkAndTheSignalPath) {
  std::mt19937_64 rng(777);
  long compared = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const int bytes = 1 + trial % 8;
    std::string text = "BO_ 5 M: " + std::to_string(bytes) + " A\n";
    const int count = 1 + static_cast<int>(rng() % 8);
    for (int k = 0; k < count; ++k) {
      const int max_len = std::min(63, 8 * bytes);
      const int len = 1 + static_cast<int>(rng() % static_cast<unsigned>(max_len));
      const bool moto = rng() % 2 == 0;
      const bool sgn = rng() % 2 == 0;
      const int lin = static_cast<int>(rng() % static_cast<unsigned>(8 * bytes - len + 1));
      const int start = moto ? (lin / 8) * 8 + (7 - lin % 8) : lin;
      text += " SG_ S" + std::to_string(k) + " : " + std::to_string(start) + "|" +
              std::to_string(len) + "@" + (moto ? "0" : "1") + (sgn ? "-" : "+") +
              " (0.5,-7) [0|0] \"\" A\n";
    }
    const Decoder d = compile_text(text);
    const Message& msg = d.database().messages[0];
    CanFrame f;
    f.id = 5;
    f.len = static_cast<std::uint8_t>(bytes);
    for (int rep = 0; rep < 4; ++rep) {
      for (std::uint8_t& b : f.data) b = static_cast<std::uint8_t>(rng());  // garbage after len
      int seen = 0;
      ASSERT_EQ(d.decode(f,
                         [&](int i, double v) {
                           ++seen;
                           const Signal& s = msg.signals[static_cast<std::size_t>(i)];
                           const std::string what = s.name + " " + std::to_string(s.start_bit) +
                                                    "|" + std::to_string(s.length) + " in " +
                                                    std::to_string(bytes) + " bytes";
                           ASSERT_EQ(v, testing::walk_physical(s, f.data)) << what;
                           double single = 0.0;
                           ASSERT_TRUE(d.signal_value(f, SignalRef{0, i}, &single));
                           ASSERT_EQ(v, single) << what;
                           ++compared;
                         }),
                DecodeStatus::kOk);
      ASSERT_EQ(seen, count);
    }
  }
  EXPECT_GT(compared, 30000);
}

TEST(DecoderWordPath, ExtendedIdTableFindsEveryIdAndNothingElse) {
  std::mt19937_64 rng(99);
  std::set<std::uint32_t> ids;
  while (ids.size() < 700) ids.insert(static_cast<std::uint32_t>(rng()) & kEffMask);
  std::string text;
  int n = 0;
  for (std::uint32_t id : ids) {
    text += "BO_ " + std::to_string(id | kDbcExtendedBit) + " E" + std::to_string(n++) + ": 8 A\n";
  }
  text += "BO_ 291 S: 8 A\n";  // 0x123 standard
  const Decoder d = compile_text(text);
  n = 0;
  for (std::uint32_t id : ids) {
    ASSERT_EQ(d.find_message(id, true), n) << id;
    ++n;
  }
  for (int i = 0; i < 20000; ++i) {
    const std::uint32_t id = static_cast<std::uint32_t>(rng()) & kEffMask;
    if (ids.count(id) == 0) {
      ASSERT_EQ(d.find_message(id, true), -1) << id;
    }
  }
  EXPECT_EQ(d.find_message(0x123, false), n);
  const Decoder empty = compile_text("BO_ 1 A: 8 A\n");
  EXPECT_EQ(empty.find_message(1, true), -1);
}

}  // namespace
}  // namespace vmass::can
