// Bad external data never crashes the CAN layer: mutated DBC files and log lines are reported,
// never fatal. (Run under the asan preset as well.)
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "vmass/can/candump.hpp"
#include "vmass/can/dbc.hpp"
#include "vmass/can/decoder.hpp"

namespace vmass::can {
namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(Robustness, MutatedDbcFilesAreReportedNotFatal) {
  const std::string original =
      read_file(std::string(VMASS_TEST_DATA_DIR) + "/dbc/toyota_prius_2010_pt.dbc");
  ASSERT_FALSE(original.empty());
  std::mt19937_64 rng(2024);
  const char alphabet[] = "0123456789 |@+-()[],:;\"\n\rABCmMxSG_BO_\xB0\xFF";
  int failed = 0, loaded = 0;
  for (int trial = 0; trial < 400; ++trial) {
    std::string text = original;
    const int edits = 1 + static_cast<int>(rng() % 8);
    for (int e = 0; e < edits; ++e) {
      const std::size_t pos = rng() % text.size();
      switch (rng() % 4) {
        case 0:
          text[pos] = alphabet[rng() % (sizeof alphabet - 1)];
          break;
        case 1:
          text.erase(pos, 1 + rng() % 20);
          break;
        case 2:
          text.insert(pos, 1, alphabet[rng() % (sizeof alphabet - 1)]);
          break;
        default:
          text.resize(pos);  // truncated file
          break;
      }
      if (text.empty()) text = "B";
    }
    const DbcParseResult r = parse_dbc(text, "mutated.dbc");
    if (!r.ok()) {
      ++failed;
      for (const DbcDiagnostic& d : r.diagnostics) {
        if (d.severity == Severity::kError) {
          EXPECT_FALSE(d.message.empty());
          EXPECT_GE(d.line, 1);
        }
      }
    }
    // Whatever was loaded compiles into tables that decode without faults.
    std::string why;
    auto decoder = Decoder::compile(r.database, &why);
    ASSERT_TRUE(decoder.has_value()) << why;
    ++loaded;
    CanFrame f;
    for (int mi = 0; mi < decoder->message_count(); ++mi) {
      const Message& m = decoder->database().messages[static_cast<std::size_t>(mi)];
      f.id = m.id;
      f.flags = m.extended ? kExtended : 0;
      f.len = static_cast<std::uint8_t>(m.length);
      for (int i = 0; i < kFdMaxLen; ++i) f.data[i] = static_cast<std::uint8_t>(rng());
      decoder->decode(f, [](int, double) {});
    }
  }
  EXPECT_GT(failed, 50);  // the mutations do break files, and those are reported
  EXPECT_EQ(loaded, 400);
}

TEST(Robustness, RandomLogLinesAreReportedNotFatal) {
  std::mt19937_64 rng(7);
  const char alphabet[] = "0123456789ABCDEFabcdef#.() R_Tcanv\t";
  std::string log;
  for (int i = 0; i < 3000; ++i) {
    std::string line = "(1700000000.000000) can0 123#00";
    const int edits = static_cast<int>(rng() % 6);
    for (int e = 0; e < edits && !line.empty(); ++e) {
      const std::size_t pos = rng() % line.size();
      if (rng() % 2) {
        line[pos] = alphabet[rng() % (sizeof alphabet - 1)];
      } else {
        line.insert(pos, std::string(1 + rng() % 80, alphabet[rng() % (sizeof alphabet - 1)]));
      }
    }
    log += line + "\n";
  }
  std::istringstream in(log);
  CandumpReader reader(in);
  CandumpRecord r;
  std::uint64_t frames = 0;
  while (reader.next(&r)) {
    ++frames;
    EXPECT_LE(r.frame.len, kFdMaxLen);
  }
  const CandumpStats& s = reader.stats();
  EXPECT_EQ(s.lines, 3000u);
  EXPECT_EQ(s.frames + s.corrupt + s.comments, 3000u);
  EXPECT_GT(s.corrupt, 100u);
  EXPECT_GT(frames, 100u);
}

}  // namespace
}  // namespace vmass::can
