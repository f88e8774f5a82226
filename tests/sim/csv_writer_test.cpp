// samples.csv and truth.csv follow docs/formats.md and read back to the same numbers.
#include <gtest/gtest.h>

#include <clocale>
#include <cstdlib>
#include <locale>
#include <sstream>

#include "sim_test_util.hpp"
#include "vmass/sim/csv_writer.hpp"

namespace vmass::sim {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream ss(line);
  while (std::getline(ss, cell, ',')) out.push_back(cell);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

TEST(SimCsv, SamplesHeaderIsTheOneInFormatsMd) {
  const std::string doc = test::read_file(test::source_path("docs/formats.md"));
  ASSERT_FALSE(doc.empty());
  const std::size_t at = doc.find("\ntime_s,wheel_torque_nm");
  ASSERT_NE(at, std::string::npos);
  const std::string line = doc.substr(at + 1, doc.find('\n', at + 1) - at - 1);
  EXPECT_EQ(line, std::string(kSamplesCsvHeader));
}

TEST(SimCsv, TruthHeaderStartsWithTheColumnsFormatsMdFixes) {
  EXPECT_EQ(truth_csv_header().rfind(
                "time_s,mass_kg,speed_mps,grade_rad,lateral_velocity_mps,yaw_rate_radps,"
                "accel_x_mps2,accel_y_mps2,",
                0),
            0u);
}

TEST(SimCsv, NumbersAreLocaleFreeAndCompact) {
  // Even under a locale with a decimal comma (when the system has one)
  const char* old = std::setlocale(LC_ALL, nullptr);
  const std::string saved = old ? old : "C";
  std::setlocale(LC_ALL, "de_DE.UTF-8");
  EXPECT_EQ(format_number(0.35), "0.35");
  EXPECT_EQ(format_number(-0.0), "0");
  EXPECT_EQ(format_number(1659.0), "1659");
  EXPECT_EQ(format_number(1e-5), "1e-05");
  EXPECT_EQ(format_number(0.1 + 0.2), "0.3");  // 12 significant digits
  EXPECT_EQ(format_number(std::nan("")), "");
  std::setlocale(LC_ALL, saved.c_str());
}

TEST(SimCsv, InvalidInputsAreEmptyCells) {
  Sample s;
  s.time_us = 1'230'000;
  s.set(Input::kSpeed, 12.5);
  s.set(Input::kGear, 3);
  std::ostringstream os;
  write_samples_csv(os, {s});
  EXPECT_EQ(os.str(), std::string(kSamplesCsvHeader) + "\n1.23,,,,,,12.5,,,3,,,\n");
}

TEST(SimCsv, SamplesReadBackToTheSimulatedValues) {
  SimulationOptions o;
  o.seed = 2;
  const SimulationResult r = test::run(*find_scenario("load_step"), o);
  std::ostringstream os;
  write_samples_csv(os, r.samples);
  std::istringstream is(os.str());
  std::string line;
  std::getline(is, line);
  std::size_t k = 0;
  while (std::getline(is, line)) {
    const std::vector<std::string> cells = split(line);
    ASSERT_EQ(cells.size(), 1u + kInputCount);
    EXPECT_EQ(from_seconds(std::strtod(cells[0].c_str(), nullptr)), r.samples[k].time_us);
    for (int i = 0; i < kInputCount; ++i) {
      const double v = r.samples[k].value(static_cast<Input>(i));
      EXPECT_NEAR(std::strtod(cells[static_cast<std::size_t>(i) + 1].c_str(), nullptr), v,
                  1e-11 * std::max(1.0, std::abs(v)));
    }
    ++k;
  }
  EXPECT_EQ(k, r.samples.size());
  // times are exact multiples of 10 ms
  EXPECT_EQ(r.samples[12345].time_us, 123'450'000);
}

TEST(SimCsv, TruthRowsHaveOneCellPerHeaderColumn) {
  const SimulationResult r = test::run(*find_scenario("steady_turn"), test::ideal());
  std::ostringstream os;
  write_truth_csv(os, r.truth);
  std::istringstream is(os.str());
  std::string line;
  std::getline(is, line);
  const std::size_t columns = split(line).size();
  EXPECT_GE(columns, 30u);
  int rows = 0;
  while (std::getline(is, line)) {
    ASSERT_EQ(split(line).size(), columns);
    ++rows;
  }
  EXPECT_EQ(rows, 6001);
}

TEST(SimCsv, WriteToAMissingDirectoryFailsWithTheFileName) {
  const SimulationResult r = test::run(*find_scenario("steady_turn"), test::ideal());
  const std::string m = write_csv_files(r, "/nonexistent_vmass_dir");
  EXPECT_NE(m.find("/nonexistent_vmass_dir/samples.csv"), std::string::npos) << m;
}

}  // namespace
}  // namespace vmass::sim
