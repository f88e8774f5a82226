// Decoder: bit extraction against an independent bit-by-bit walk, multiplexing, rejection of
// short frames, encode -> decode identity, and no allocation while decoding.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <new>
#include <random>
#include <string>

#include "allocation_counter.hpp"
#include "bit_walk.hpp"
#include "vmass/can/decoder.hpp"

namespace vmass::can {
namespace {

using testing::walk_physical;
using testing::walk_raw;

const std::string kDataDir = VMASS_TEST_DATA_DIR;

bool walk_present(const Message& m, int i, const std::uint8_t* data) {
  const Signal& s = m.signals[static_cast<std::size_t>(i)];
  if (s.mux_parent < 0) return true;
  if (!walk_present(m, s.mux_parent, data)) return false;
  const std::uint64_t sw = walk_raw(m.signals[static_cast<std::size_t>(s.mux_parent)], data);
  for (const MuxRange& r : s.mux_ranges) {
    if (sw >= r.lo && sw <= r.hi) return true;
  }
  return false;
}

void expect_same(double a, double b, const std::string& what) {
  if (std::isnan(a) || std::isnan(b)) {
    EXPECT_TRUE(std::isnan(a) && std::isnan(b)) << what;
  } else {
    EXPECT_EQ(a, b) << what;
  }
}

Decoder compile_text(const std::string& text) {
  DbcParseResult r = parse_dbc(text, "test.dbc");
  EXPECT_TRUE(r.ok());
  std::string err;
  auto d = Decoder::compile(std::move(r.database), &err);
  EXPECT_TRUE(d.has_value()) << err;
  return std::move(*d);
}

TEST(Decoder, HandComputedLayouts) {
  const Decoder d = compile_text(
      "BO_ 1 M: 8 A\n"
      " SG_ LeU16 : 0|16@1+ (1,0) [0|0] \"\" A\n"
      " SG_ BeU16 : 23|16@0+ (1,0) [0|0] \"\" A\n"  // MSB at bit 23 (byte 2): bytes 2,3
      " SG_ BeNib : 35|6@0- (1,0) [0|0] \"\" A\n"   // byte 4 bits 3..0 then byte 5 bits 7..6
      " SG_ LeOdd : 44|12@1- (0.5,10) [0|0] \"\" A\n");
  CanFrame f;
  f.id = 1;
  f.len = 8;
  const std::uint8_t bytes[8] = {0x34, 0x12, 0xAB, 0xCD, 0x0A, 0x40, 0xF0, 0xFF};
  std::memcpy(f.data, bytes, 8);
  double v[4] = {};
  std::uint8_t present[4] = {};
  int m = -1;
  ASSERT_EQ(d.decode_into(f, &m, v, present), DecodeStatus::kOk);
  EXPECT_EQ(m, 0);
  EXPECT_EQ(v[0], 0x1234);
  EXPECT_EQ(v[1], 0xABCD);
  // byte 4 low nibble 1010, byte 5 top two bits 01 -> 101001b = 41 -> signed 6 bits = -23
  EXPECT_EQ(v[2], -23);
  // bits 44..55: byte 5 high nibble (0x4) then byte 6 (0xF0) -> 0xF04 -> signed 12 bits = -252
  EXPECT_EQ(v[3], -252 * 0.5 + 10);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(present[i], 1);
}

// Random layouts in classic and FD payloads: compiled extraction equals the bit walk.
TEST(Decoder, RandomLayoutsMatchTheBitWalk) {
  std::mt19937_64 rng(12345);
  for (int trial = 0; trial < 300; ++trial) {
    const int bytes = trial % 3 == 0 ? 64 : 8;
    std::string text = "BO_ 1 M: " + std::to_string(bytes) + " A\n";
    for (int k = 0; k < 6; ++k) {
      const int len = 1 + static_cast<int>(rng() % 64);
      const bool moto = rng() % 2 == 0;
      const bool sgn = rng() % 2 == 0;
      int start = 0;
      if (!moto) {
        start = static_cast<int>(rng() % static_cast<unsigned>(8 * bytes - len + 1));
      } else {
        // pick the MSB's linear position so that the LSB stays inside, then convert
        const int lin = static_cast<int>(rng() % static_cast<unsigned>(8 * bytes - len + 1));
        start = (lin / 8) * 8 + (7 - lin % 8);
      }
      text += " SG_ S" + std::to_string(k) + " : " + std::to_string(start) + "|" +
              std::to_string(len) + "@" + (moto ? "0" : "1") + (sgn ? "-" : "+") +
              " (0.25,-3) [0|0] \"\" A\n";
    }
    const Decoder d = compile_text(text);
    const Message& msg = d.database().messages[0];
    CanFrame f;
    f.id = 1;
    f.len = static_cast<std::uint8_t>(bytes);
    for (int rep = 0; rep < 5; ++rep) {
      for (int i = 0; i < bytes; ++i) f.data[i] = static_cast<std::uint8_t>(rng());
      int seen = 0;
      d.decode(f, [&](int i, double v) {
        ++seen;
        const Signal& s = msg.signals[static_cast<std::size_t>(i)];
        expect_same(v, walk_physical(s, f.data),
                    s.name + " " + std::to_string(s.start_bit) + "|" + std::to_string(s.length));
      });
      EXPECT_EQ(seen, 6);
    }
  }
}

// Every message of every real DBC: decode equals the walk, and exactly the signals the
// multiplexor selects are reported.
TEST(Decoder, RealFilesMatchTheBitWalk) {
  std::mt19937_64 rng(777);
  for (const char* name : {"vw_mqb.dbc", "toyota_prius_2010_pt.dbc", "toyota_2017_ref_pt.dbc",
                           "FORD_CADS_64.dbc", "tesla_model3_vehicle.dbc", "hyundai_2015_mcan.dbc",
                           "gm_global_a_high_voltage_management.dbc"}) {
    DbcParseResult r = load_dbc_file(kDataDir + "/dbc/" + name);
    std::string err;
    auto d = Decoder::compile(r.database, &err);
    ASSERT_TRUE(d.has_value()) << name << ": " << err;
    for (int mi = 0; mi < d->message_count(); ++mi) {
      const Message& m = d->database().messages[static_cast<std::size_t>(mi)];
      CanFrame f;
      f.id = m.id;
      f.flags = m.extended ? kExtended : 0;
      f.len = static_cast<std::uint8_t>(m.length);
      for (int rep = 0; rep < 20; ++rep) {
        for (int i = 0; i < m.length; ++i) f.data[i] = static_cast<std::uint8_t>(rng());
        // Small switch values so that multiplexed signals are selected often.
        for (const Signal& s : m.signals) {
          if (s.is_multiplexor && rep % 2 == 0) {
            d->encode_signal(SignalRef{mi, m.find_signal(s.name)}, static_cast<double>(rep % 4),
                             f.data);
          }
        }
        std::vector<int> seen(m.signals.size(), 0);
        ASSERT_EQ(d->decode(f,
                            [&](int i, double v) {
                              seen[static_cast<std::size_t>(i)] = 1;
                              expect_same(
                                  v, walk_physical(m.signals[static_cast<std::size_t>(i)], f.data),
                                  std::string(name) + " " + m.name + "." +
                                      m.signals[static_cast<std::size_t>(i)].name);
                            }),
                  DecodeStatus::kOk);
        for (std::size_t i = 0; i < m.signals.size(); ++i) {
          EXPECT_EQ(seen[i], walk_present(m, static_cast<int>(i), f.data) ? 1 : 0)
              << name << " " << m.name << "." << m.signals[i].name;
        }
      }
    }
  }
}

const char* kMux =
    "BO_ 2147484672 X: 16 A\n"
    " SG_ Mode M : 0|8@1+ (1,0) [0|0] \"\" A\n"
    " SG_ Sub m1M : 8|8@1+ (1,0) [0|0] \"\" A\n"
    " SG_ A m0 : 16|16@1- (1,0) [0|0] \"\" A\n"
    " SG_ B m1 : 16|16@1+ (1,0) [0|0] \"\" A\n"
    " SG_ C : 32|32@1- (1,0) [0|0] \"\" A\n"
    " SG_ D : 64|64@1- (1,0) [0|0] \"\" A\n"
    "SIG_VALTYPE_ 2147484672 C : 1;\n"
    "SIG_VALTYPE_ 2147484672 D : 2;\n"
    "SG_MUL_VAL_ 2147484672 Sub Mode 1-1;\n"
    "SG_MUL_VAL_ 2147484672 A Mode 0-0;\n"
    "SG_MUL_VAL_ 2147484672 B Sub 3-5, 9-9;\n";

TEST(Decoder, ExtendedMultiplexingAndFloats) {
  const Decoder d = compile_text(kMux);
  CanFrame f;
  f.id = 0x400;
  f.flags = kExtended | kFd;
  f.len = 16;
  const float c = -1.5f;
  const double dd = 6.02e23;
  std::memcpy(f.data + 4, &c, 4);  // little-endian host = Intel layout
  std::memcpy(f.data + 8, &dd, 8);
  auto present = [&](std::uint8_t mode, std::uint8_t sub) {
    f.data[0] = mode;
    f.data[1] = sub;
    f.data[2] = 0xFE;
    f.data[3] = 0xFF;
    std::string names;
    d.decode(f, [&](int i, double) {
      names += d.database().messages[0].signals[static_cast<std::size_t>(i)].name;
    });
    return names;
  };
  EXPECT_EQ(present(0, 4), "ModeCDA");  // by depth in the switch tree, DBC order within a depth
  EXPECT_EQ(present(1, 4), "ModeCDSubB");
  EXPECT_EQ(present(1, 9), "ModeCDSubB");
  EXPECT_EQ(present(1, 6), "ModeCDSub");
  EXPECT_EQ(present(2, 4), "ModeCD");
  double values[6];
  std::uint8_t flags[6];
  f.data[0] = 0;
  ASSERT_EQ(d.decode_into(f, nullptr, values, flags), DecodeStatus::kOk);
  EXPECT_EQ(values[2], -2);       // A: 0xFFFE signed
  EXPECT_EQ(values[4], -1.5);     // C float32
  EXPECT_EQ(values[5], 6.02e23);  // D float64
  EXPECT_EQ(flags[1], 0);
  EXPECT_EQ(flags[3], 0);
}

TEST(Decoder, RejectsShortUnknownRemoteAndErrorFramesAndCountsThem) {
  const Decoder d = compile_text("BO_ 16 M: 8 A\n SG_ S : 56|8@1+ (1,0) [0|0] \"\" A\n");
  DecodeStats stats;
  CanFrame f;
  f.id = 16;
  f.len = 7;  // shorter than the DBC's 8: rejected, never zero-filled
  int calls = 0;
  auto sink = [&](int, double) { ++calls; };
  stats.count(d.decode(f, sink));
  f.len = 8;
  f.flags = kRemote;
  stats.count(d.decode(f, sink));
  f.flags = kExtended;  // same number as an extended id: a different message
  stats.count(d.decode(f, sink));
  f.flags = kError;
  stats.count(d.decode(f, sink));
  f.flags = 0;
  f.data[7] = 9;
  stats.count(d.decode(f, sink));
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(stats.frames, 5u);
  EXPECT_EQ(stats.too_short, 1u);
  EXPECT_EQ(stats.remote, 1u);
  EXPECT_EQ(stats.unknown_id, 1u);
  EXPECT_EQ(stats.error_frames, 1u);
  EXPECT_EQ(stats.decoded, 1u);
  double v = 0;
  f.len = 7;
  EXPECT_FALSE(d.signal_value(f, SignalRef{0, 0}, &v));
  f.len = 12;  // longer than the DBC says: decoded
  EXPECT_TRUE(d.signal_value(f, SignalRef{0, 0}, &v));
  EXPECT_EQ(v, 9);
}

TEST(Decoder, EncodeThenDecodeIsIdentityAndClamps) {
  const Decoder d = compile_text(
      "BO_ 5 M: 8 A\n"
      " SG_ U : 0|12@1+ (0.1,-20) [0|0] \"\" A\n"
      " SG_ S : 23|10@0- (0.5,0) [0|0] \"\" A\n"
      " SG_ W : 39|28@0+ (1,0) [0|0] \"\" A\n"
      " SG_ Big : 56|1@1+ (1,0) [0|0] \"\" A\n");
  std::mt19937_64 rng(99);
  for (int trial = 0; trial < 2000; ++trial) {
    const double u = -20 + 0.1 * static_cast<double>(rng() % 4096);
    const double s = 0.5 * (static_cast<double>(rng() % 1024) - 512);
    const double w = static_cast<double>(rng() % (1u << 28));
    const double big = static_cast<double>(rng() % 2);
    const double in[4] = {u, s, w, big};
    CanFrame f;
    ASSERT_TRUE(d.encode(0, in, &f));
    EXPECT_EQ(f.id, 5u);
    EXPECT_EQ(f.len, 8);
    double out[4];
    std::uint8_t present[4];
    ASSERT_EQ(d.decode_into(f, nullptr, out, present), DecodeStatus::kOk);
    EXPECT_NEAR(out[0], u, 1e-9);
    EXPECT_EQ(out[1], s);
    EXPECT_EQ(out[2], w);
    EXPECT_EQ(out[3], big);
    // Independent check of the written bits.
    EXPECT_EQ(walk_raw(d.database().messages[0].signals[2], f.data), static_cast<std::uint64_t>(w));
  }
  // Rounding to the nearest raw step and clamping to the bit width.
  const CompiledSignal& cu = d.compiled(SignalRef{0, 0});
  EXPECT_EQ(d.physical_to_raw(cu, -19.94), 1u);  // (−19.94+20)/0.1 = 0.6 -> 1
  EXPECT_EQ(d.physical_to_raw(cu, 1e9), 4095u);
  EXPECT_EQ(d.physical_to_raw(cu, -1e9), 0u);
  const CompiledSignal& cs = d.compiled(SignalRef{0, 1});
  EXPECT_EQ(d.physical_to_raw(cs, 1e9), 511u);
  EXPECT_EQ(d.physical_to_raw(cs, -1e9), 512u);  // -512 in 10 bits
  EXPECT_EQ(d.physical_to_raw(cs, std::nan("")), 0u);
}

TEST(Decoder, EncodeWritesOnlyWhatTheMultiplexorSelects) {
  const Decoder d = compile_text(kMux);
  double in[6] = {1, 4, 123, 77, 2.5, -8};
  CanFrame f;
  ASSERT_TRUE(d.encode(0, in, &f));
  EXPECT_TRUE(f.extended());
  EXPECT_TRUE(f.fd());
  double out[6];
  std::uint8_t present[6];
  ASSERT_EQ(d.decode_into(f, nullptr, out, present), DecodeStatus::kOk);
  EXPECT_EQ(present[2], 0);  // A needs Mode 0
  EXPECT_EQ(present[3], 1);
  EXPECT_EQ(out[3], 77);
  EXPECT_EQ(out[4], 2.5);
  EXPECT_EQ(out[5], -8);
}

TEST(Decoder, SelectionDecodesNamedSignalsIntoSlots) {
  DbcParseResult r = load_dbc_file(kDataDir + "/dbc/vw_mqb.dbc");
  const auto d = Decoder::compile(r.database);
  ASSERT_TRUE(d.has_value());
  SignalSelection sel(*d);
  const SignalRef speed = d->find_signal("ESP_21", "ESP_v_Signal");
  const SignalRef angle = d->find_signal("LWI_01", "LWI_Lenkradwinkel");
  ASSERT_TRUE(speed.valid());
  ASSERT_TRUE(angle.valid());
  EXPECT_FALSE(d->find_signal("ESP_21", "nope").valid());
  EXPECT_FALSE(d->find_signal("nope", "ESP_v_Signal").valid());
  EXPECT_EQ(sel.add(angle), 0);
  EXPECT_EQ(sel.add(speed), 1);
  EXPECT_EQ(sel.add(SignalRef{}), -1);

  std::vector<double> values(static_cast<std::size_t>(d->max_signals_per_message()), 0.0);
  values[static_cast<std::size_t>(speed.signal)] = 123.45;
  CanFrame f;
  ASSERT_TRUE(d->encode(speed.message, values.data(), &f));
  double slots[2] = {0, 0};
  int updates = 0;
  const long before = testing::allocations();
  const DecodeStatus st = sel.decode(f, [&](int slot, double v) {
    slots[slot] = v;
    ++updates;
  });
  EXPECT_EQ(testing::allocations(), before);
  ASSERT_EQ(st, DecodeStatus::kOk);
  EXPECT_EQ(updates, 1);
  EXPECT_NEAR(slots[1], 123.45, 1e-9);
}

TEST(Decoder, DecodingAllocatesNothing) {
  if (!testing::counting_allocations())
    GTEST_SKIP() << "allocation counting is off under sanitizers";
  DbcParseResult r = load_dbc_file(kDataDir + "/dbc/FORD_CADS_64.dbc");
  const auto d = Decoder::compile(r.database);
  ASSERT_TRUE(d.has_value());
  std::vector<CanFrame> frames;
  std::mt19937_64 rng(5);
  for (int mi = 0; mi < d->message_count(); ++mi) {
    const Message& m = d->database().messages[static_cast<std::size_t>(mi)];
    CanFrame f;
    f.id = m.id;
    f.flags = static_cast<std::uint8_t>((m.extended ? kExtended : 0) | (m.fd ? kFd : 0));
    f.len = static_cast<std::uint8_t>(m.length);
    for (int i = 0; i < m.length; ++i) f.data[i] = static_cast<std::uint8_t>(rng());
    frames.push_back(f);
  }
  std::vector<double> values(static_cast<std::size_t>(d->max_signals_per_message()));
  std::vector<std::uint8_t> present(values.size());
  double sum = 0.0;
  const long before = testing::allocations();
  for (const CanFrame& f : frames) {
    d->decode(f, [&](int, double v) { sum += v; });
    d->decode_into(f, nullptr, values.data(), present.data());
  }
  EXPECT_EQ(testing::allocations(), before);
  EXPECT_TRUE(std::isfinite(sum) || std::isnan(sum));
}

TEST(Decoder, LookupByIdAndKind) {
  const Decoder d =
      compile_text("BO_ 2047 Std: 1 A\nBO_ 2147485695 Ext: 1 A\nBO_ 2684354559 ExtMax: 1 A\n");
  EXPECT_EQ(d.find_message(0x7FF, false), 0);
  EXPECT_EQ(d.find_message(0x7FF, true), 1);
  EXPECT_EQ(d.find_message(0x1FFFFFFF, true), 2);
  EXPECT_EQ(d.find_message(0x1FFFFFFE, true), -1);
  EXPECT_EQ(d.find_message(0x800, false), -1);
  EXPECT_EQ(d.find_message("ExtMax"), 2);
}

}  // namespace
}  // namespace vmass::can
