// A config's cost is bounded whatever its text: nested YAML anchors and aliases ("billion
// laughs") expand to a tree of billions of nodes that any walk of it would take hours over; the
// loader refuses a tree of more than 100,000 nodes with the file and the line, at once. An
// anchor used as YAML intends it, a few times, still loads.
#include <gtest/gtest.h>

#include <string>

#include "vmass/config/config.hpp"

namespace vmass {
namespace {

const char* kVehicle = R"(vehicle:
  empty_mass_kg: 1500
  wheelbase_m: 2.7
  cg_to_front_axle_m: 1.2
  wheel_radius_m: 0.31
  brake_gain_n_per_pa: 0.0033
  steering_ratio: 15.5
  cornering_stiffness_front_n_per_rad: 150000
  cornering_stiffness_rear_n_per_rad: 170000
)";

/// levels of anchors, each a list of ten aliases of the one before: 10^levels nodes.
std::string laughs(int levels) {
  std::string text = std::string(kVehicle) + "x0: &l0 [lol]\n";
  for (int i = 1; i <= levels; ++i) {
    const std::string prev = "*l" + std::to_string(i - 1);
    text += "x" + std::to_string(i) + ": &l" + std::to_string(i) + " [";
    for (int k = 0; k < 10; ++k) text += (k ? ", " : "") + prev;
    text += "]\n";
  }
  return text;
}

// Without the bound this test does not finish within ctest's timeout: the walk of 10^9 nodes.
TEST(BoundedConfig, NestedAliasesAreRefusedWithTheFileAndLine) {
  const ConfigLoad c = load_config_text(laughs(9), "laughs.yaml");
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.error.find("laughs.yaml:"), std::string::npos) << c.error;
  EXPECT_NE(c.error.find("more than 100000 nodes"), std::string::npos) << c.error;
}

// An alias inside the node it names is a cycle (the fuzzer found it: a stack overflow in the
// walk). Refused at its line, whatever the depth of the text.
TEST(BoundedConfig, AnAliasInsideItsOwnNodeIsRefused) {
  for (const char* cycle : {"x: &a [1, *a]\n", "x: &m {k: *m}\n"}) {
    const ConfigLoad c = load_config_text(std::string(kVehicle) + cycle, "cycle.yaml");
    ASSERT_FALSE(c.ok()) << cycle;
    EXPECT_NE(c.error.find("cycle.yaml:"), std::string::npos) << c.error;
    EXPECT_NE(c.error.find("nested more than 64 levels"), std::string::npos) << c.error;
  }
}

TEST(BoundedConfig, AnAnchorUsedAFewTimesStillLoads) {
  // Aliases as YAML means them: one shared value; the unknown key under it is still reported.
  const std::string ok = std::string(kVehicle) + "suspension: &s\n  stiffness_n_per_m: 30000\n";
  EXPECT_TRUE(load_config_text(ok, "anchor.yaml").ok());
  const ConfigLoad small = load_config_text(laughs(3), "small.yaml");  // 1,000 nodes
  ASSERT_FALSE(small.ok());
  EXPECT_EQ(small.error.find("more than 100000 nodes"), std::string::npos) << small.error;
  EXPECT_NE(small.error.find("x0"), std::string::npos) << small.error;  // an unknown key
}

// A null is not a default: `key: ~` or `key:` with nothing after it is refused with its line.
TEST(StrictConfig, ANullValueIsAnErrorNotADefault) {
  for (const char* value : {"~", "", "null"}) {
    const std::string text = std::string(kVehicle) + "estimator:\n  tick_rate_hz: " + value + "\n";
    const ConfigLoad c = load_config_text(text, "null.yaml");
    ASSERT_FALSE(c.ok()) << "'" << value << "' was accepted";
    EXPECT_NE(c.error.find("null.yaml:"), std::string::npos) << c.error;
    EXPECT_NE(c.error.find("estimator.tick_rate_hz: no value"), std::string::npos) << c.error;
  }
}

// One YAML document: a second one, or anything after the end marker, would be read by nobody.
TEST(StrictConfig, ASecondYamlDocumentIsRefused) {
  for (const char* tail : {"---\nvehicle:\n  empty_mass_kg: 9\n", "...\ngarbage: 1\n"}) {
    const ConfigLoad c = load_config_text(std::string(kVehicle) + tail, "two.yaml");
    ASSERT_FALSE(c.ok()) << tail;
    EXPECT_NE(c.error.find("two.yaml:"), std::string::npos) << c.error;
  }
}

// A NUL byte is no YAML text: refused at its line. yaml-cpp's LoadAll, which the loader once
// used to find a second document, never ended on such a text (the fuzzer's 2 GB of empty
// documents, fuzz/corpus/fuzz_config/regression_loadall_nul.yaml); it reads two at most now.
TEST(StrictConfig, ANulByteIsRefusedAtItsLine) {
  const std::string text = std::string(kVehicle) + "x: a" + std::string(1, '\0') + "b\n";
  const ConfigLoad c = load_config_text(text, "nul.yaml");
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.error.find("nul.yaml:10: a NUL byte"), std::string::npos) << c.error;
}

}  // namespace
}  // namespace vmass
