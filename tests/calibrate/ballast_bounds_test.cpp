// Given ballast data a hostile tester wrote (absurd masses and deflections, decimal commas, rows
// cut short, a spreadsheet's byte order mark) or a fit the config loader would refuse, when it is
// read or checked, then it is refused with file:line, the column, the value and the bound, or
// (the byte order mark) read as if it were not there.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "synthetic_ballast.hpp"
#include "vmass/calibrate/ballast_csv.hpp"
#include "vmass/calibrate/calibration_report.hpp"
#include "vmass/calibrate/suspension_fit.hpp"

namespace vmass::calibrate {
namespace {

std::string error_of(const std::string& text) {
  const BallastCsvRead r = parse_ballast_csv(text, "b.csv");
  EXPECT_FALSE(r.ok()) << text;
  return r.error;
}

const char* const kStepsHeader = "added_mass_kg,rear_right_deflection_mm\n";

TEST(BallastBounds, AbsurdAddedMassesNameTheLineValueAndBound) {
  EXPECT_EQ(error_of(std::string(kStepsHeader) + "0,12\n1e9,19\n"),
            "b.csv:3: added_mass_kg: 1e+09 kg is outside [-1000, 100000] kg (ballast added to "
            "one vehicle; a unit error?)");
  EXPECT_NE(error_of(std::string(kStepsHeader) + "-1000.5,12\n").find("b.csv:2: added_mass_kg: "),
            std::string::npos);
  // The bound is on the SI value: 200 t is 200000 kg.
  EXPECT_NE(error_of("added_mass_t,rear_right_deflection_mm\n0,12\n200,19\n")
                .find("b.csv:3: added_mass_t: 200000 kg is outside"),
            std::string::npos);
  const BallastCsvRead edge =
      parse_ballast_csv(std::string(kStepsHeader) + "-1000,11\n100000,19\n", "b.csv");
  EXPECT_TRUE(edge.ok()) << edge.error;
}

TEST(BallastBounds, MassListsAreHeldToTheSameBound) {
  std::vector<double> m;
  EXPECT_EQ(parse_mass_list("0,1e9", &m),
            "masses: 1e+09 kg is outside [-1000, 100000] kg (ballast added to one vehicle; a "
            "unit error?)");
  EXPECT_NE(parse_mass_list("0:50000:150000", &m), "");
  EXPECT_EQ(parse_mass_list("0:50000:100000", &m), "");
}

TEST(BallastBounds, DeflectionsBeyondOneMetreAreRefusedInStepsAndSeries) {
  EXPECT_EQ(error_of("added_mass_kg,rear_right_deflection_m\n0,10\n100,20\n"),
            "b.csv:2: rear_right_deflection_m: 10 m is outside [-1, 1] m (a suspension travels "
            "well under 0.5 m; a unit error?)");
  EXPECT_NE(error_of(std::string(kStepsHeader) + "0,12\n100,1000.5\n")
                .find("b.csv:3: rear_right_deflection_mm: 1.0005 m is outside [-1, 1] m"),
            std::string::npos);
  EXPECT_NE(error_of("time_s,rear_right_deflection_m\n0,0.012\n0.01,\n0.02,-15\n")
                .find("b.csv:4: rear_right_deflection_m: -15 m is outside"),
            std::string::npos);
  const BallastCsvRead edge = parse_ballast_csv(std::string(kStepsHeader) + "0,1000\n", "b.csv");
  EXPECT_TRUE(edge.ok()) << edge.error;
}

TEST(BallastBounds, RowsWithMoreFieldsThanTheHeaderSuspectDecimalCommas) {
  // "100,13,3": 100 kg and 13.3 mm with a decimal comma, which would read as 13 mm.
  EXPECT_EQ(error_of(std::string(kStepsHeader) + "0,12\n100,13,3\n"),
            "b.csv:3: 3 fields, the header has 2; decimal commas? (write 13.3, not 13,3)");
  EXPECT_NE(error_of("time_s,rear_right_deflection_mm\n0,12\n0,01,12,1\n")
                .find("b.csv:3: 4 fields, the header has 2; decimal commas?"),
            std::string::npos);
}

TEST(BallastBounds, RowsWithFewerFieldsThanTheHeaderAreRefused) {
  // The missing field is an unused column: the row would otherwise be read as if complete.
  EXPECT_EQ(error_of("added_mass_kg,rear_right_deflection_mm,note\n0,12,a\n100,19\n"),
            "b.csv:3: 2 fields, the header has 3; a row cut short? (an empty cell keeps its "
            "comma)");
  EXPECT_NE(error_of("time_s,rear_right_deflection_m,speed_mps\n0,0.012,0\n0.01,0.012\n")
                .find("b.csv:3: 2 fields, the header has 3"),
            std::string::npos);
  const BallastCsvRead empty_cells =
      parse_ballast_csv("time_s,rear_right_deflection_m,speed_mps\n0,0.012,\n0.01,,\n", "b.csv");
  EXPECT_TRUE(empty_cells.ok()) << empty_cells.error;
}

TEST(BallastBounds, AUtf8ByteOrderMarkIsIgnored) {
  const BallastCsvRead r = parse_ballast_csv(
      "\xEF\xBB\xBF"
      "added_mass_kg,rear_right_deflection_mm\r\n0,12\r\n100,19.5\r\n",
      "b.csv");
  ASSERT_TRUE(r.ok()) << r.error;
  ASSERT_EQ(r.csv->samples.size(), 2u);
  EXPECT_NEAR(r.csv->samples[1].deflection_m, 0.0195, 1e-15);
  const BallastCsvRead series =
      parse_ballast_csv("\xEF\xBB\xBFtime_s,rear_right_deflection_m\n0,0.012\n", "b.csv");
  ASSERT_TRUE(series.ok()) << series.error;
  EXPECT_EQ(series.csv->kind, BallastCsvKind::kSeries);
}

TEST(BallastBounds, SnippetsTheConfigLoaderRefusesAreNamed) {
  EXPECT_EQ(check_suspension_yaml("suspension:\n  stiffness_n_per_m: 30000\n"), "");
  EXPECT_EQ(check_suspension_yaml("suspension:\n  stiffness_n_per_m: 6.9e11\n"),
            "suspension.stiffness_n_per_m: 6.9e+11 is beyond any plausible value "
            "(|x| <= 1e+10 N/m)");
  EXPECT_NE(check_suspension_yaml("suspension:\n  stiffness_n_per_m: 30000\n"
                                  "  progressive_knee_m: 0.04\n"
                                  "  progressive_rate_n_per_m2: 3e12\n")
                .find("suspension.progressive_rate_n_per_m2: 3e+12 is beyond"),
            std::string::npos);
  EXPECT_NE(check_suspension_yaml("suspension:\n  stiffness_n_per_m: 0\n")
                .find("suspension.stiffness_n_per_m must be > 0"),
            std::string::npos);
}

TEST(BallastBounds, AFitStifferThanTheLoaderAcceptsIsRefusedAsWritten) {
  // Deflection steps of 0.07 um per 100 kg: what millimetres read as metres would fit.
  SuspensionParams truth = testing::true_linear();
  truth.stiffness_n_per_m = 3e10;
  const auto steps = testing::make_steps(truth, testing::paper_geometry(), 5, 0.0, 1);
  const SuspensionFitResult r = fit_suspension(steps, testing::paper_geometry());
  ASSERT_TRUE(r.ok()) << r.error;
  const std::string why = check_suspension_yaml(suspension_yaml(*r.calibration));
  EXPECT_NE(why.find("suspension.stiffness_n_per_m: "), std::string::npos) << why;
  EXPECT_NE(why.find("(|x| <= 1e+10 N/m)"), std::string::npos) << why;
  // A physical fit passes: the check refuses only what the loader would.
  const auto good =
      testing::make_steps(testing::true_linear(), testing::paper_geometry(), 5, 0.0, 1);
  const SuspensionFitResult g = fit_suspension(good, testing::paper_geometry());
  ASSERT_TRUE(g.ok()) << g.error;
  EXPECT_EQ(check_suspension_yaml(suspension_yaml(*g.calibration)), "");
}

}  // namespace
}  // namespace vmass::calibrate
