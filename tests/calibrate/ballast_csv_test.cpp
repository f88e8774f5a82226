// Given ballast CSV text, when it is parsed, then units come from the column names, samples
// are grouped into steps, a time series is recognised, and every bad input names file:line,
// the column and the problem.
#include "vmass/calibrate/ballast_csv.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace vmass::calibrate {
namespace {

TEST(BallastCsv, PerSampleRowsAreGroupedIntoStepsInSiUnits) {
  const BallastCsvRead r = parse_ballast_csv(
      "# static test, 2 samples per step\r\n"
      "added_mass_kg, rear_right_deflection_mm, note\r\n"
      "100, 19.0, a\r\n"
      "0, 12.0, b\n"
      "100, 19.2, c\n"
      "\n"
      "0, 12.2, d\n"
      "200, 26.3, e\n",
      "t.csv");
  ASSERT_TRUE(r.ok()) << r.error;
  ASSERT_EQ(r.csv->kind, BallastCsvKind::kSteps);
  ASSERT_EQ(r.csv->samples.size(), 5u);
  const auto steps = group_samples(r.csv->samples);
  ASSERT_EQ(steps.size(), 3u);
  EXPECT_EQ(steps[0].added_mass_kg, 0.0);
  EXPECT_NEAR(steps[0].deflection_m, 0.0121, 1e-12);
  EXPECT_NEAR(steps[0].deflection_std_m, std::sqrt(0.02e-6), 1e-12);  // (0.1 mm)^2 * 2 / 1
  EXPECT_EQ(steps[0].sample_count, 2);
  EXPECT_NEAR(steps[1].deflection_m, 0.0191, 1e-12);
  EXPECT_EQ(steps[2].sample_count, 1);
  EXPECT_EQ(steps[2].deflection_std_m, 0.0);
}

TEST(BallastCsv, OtherUnitsConvert) {
  const BallastCsvRead r =
      parse_ballast_csv("rear_right_deflection_in,added_mass_lb\n1.0,220.46226218\n", "u.csv");
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_NEAR(r.csv->samples[0].deflection_m, 0.0254, 1e-15);
  EXPECT_NEAR(r.csv->samples[0].added_mass_kg, 100.0, 1e-6);
}

TEST(BallastCsv, TimeSeriesIsRecognisedAndEmptyCellsSkipRows) {
  const BallastCsvRead r = parse_ballast_csv(
      "time_s,speed_mps,rear_right_deflection_m\n0.00,0,0.012\n0.01,,0.0121\n0.02,0,\n", "s.csv");
  ASSERT_TRUE(r.ok()) << r.error;
  ASSERT_EQ(r.csv->kind, BallastCsvKind::kSeries);
  ASSERT_EQ(r.csv->series.size(), 2u);
  EXPECT_EQ(r.csv->skipped_rows, 1);
  EXPECT_TRUE(std::isnan(r.csv->series[1].speed_mps));  // unknown speed: assumed standing
  EXPECT_NEAR(r.csv->series[1].deflection_m, 0.0121, 1e-15);
}

struct BadCase {
  const char* text;
  const char* expected;
};

TEST(BallastCsv, BadInputNamesTheProblem) {
  const BadCase cases[] = {
      {"added_mass_kg,rear_right_deflection_furlong\n0,1\n", "unknown unit 'furlong'"},
      {"added_mass_kg,rear_right_deflection\n0,1\n", "has no unit"},
      {"added_mass_stone,rear_right_deflection_mm\n0,1\n", "unknown unit 'stone'"},
      {"added_mass_kg,rear_right_deflection_mm\n0,12.0\n100,nan\n",
       "b.csv:3: "
       "rear_right_deflection_mm: NaN"},
      {"added_mass_kg,rear_right_deflection_mm\n0,12.0\n100,19.3mm\n", "'19.3mm' is not a number"},
      {"added_mass_kg,rear_right_deflection_mm\n0,12\n100 kg,19\n", "'100 kg' is not a number"},
      {"added_mass_kg,rear_right_deflection_mm\n0,12\n100,\n", "empty cell"},
      {"added_mass_kg,rear_right_deflection_mm\n0,inf\n", "infinite"},
      {"added_mass_kg,rear_right_deflection_mm\n0\n", "b.csv:2: 1 field, the header has 2"},
      {"added_mass_kg,deflection_mm\n0,1\n", "no rear_right_deflection_<unit> column"},
      {"mass,rear_right_deflection_mm\n0,1\n", "need an added_mass_<unit> column"},
      {"added_mass_kg,rear_right_deflection_mm\n", "no data rows"},
      {"", "empty file"},
      {"added_mass_kg,added_mass_lb,rear_right_deflection_mm\n0,0,1\n", "two added_mass columns"},
  };
  for (const BadCase& c : cases) {
    const BallastCsvRead r = parse_ballast_csv(c.text, "b.csv");
    EXPECT_FALSE(r.ok()) << c.text;
    EXPECT_NE(r.error.find(c.expected), std::string::npos) << "input:\n"
                                                           << c.text << "error: " << r.error;
  }
}

TEST(BallastCsv, MassListsParse) {
  std::vector<double> m;
  EXPECT_EQ(parse_mass_list("0, 100,200", &m), "");
  EXPECT_EQ(m, (std::vector<double>{0, 100, 200}));
  EXPECT_EQ(parse_mass_list("0:100:800", &m), "");
  ASSERT_EQ(m.size(), 9u);
  EXPECT_EQ(m.back(), 800.0);
  EXPECT_NE(parse_mass_list("0,abc", &m).find("'abc' is not a number"), std::string::npos);
  EXPECT_NE(parse_mass_list("0:0:800", &m).find("STEP > 0"), std::string::npos);
  EXPECT_NE(parse_mass_list("0,nan", &m), "");
}

}  // namespace
}  // namespace vmass::calibrate
