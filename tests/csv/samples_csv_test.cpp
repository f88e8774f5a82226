// The samples CSV reader: empty cells are invalid inputs, bad rows are reported and skipped.
#include "vmass/csv/samples_csv.hpp"

#include <cstdio>
#include <fstream>

#include <gtest/gtest.h>

namespace vmass {
namespace {

std::string write_temp(const std::string& text) {
  char name[] = "/tmp/vmass_samples_XXXXXX";
  const int fd = mkstemp(name);
  EXPECT_GE(fd, 0);
  std::ofstream(name) << text;
  return name;
}

const char* kHeader =
    "time_s,wheel_torque_nm,brake_pressure_pa,accel_x_mps2,accel_y_mps2,yaw_rate_radps,speed_mps,"
    "steering_wheel_angle_rad,rear_right_deflection_m,gear\n";

TEST(SamplesCsv, EmptyCellsAreInvalidAndBadRowsAreSkipped) {
  const std::string path = write_temp(std::string(kHeader) +
                                      "0.00,100,0,0.1,0,0,10,0,0.02,3\n"
                                      "0.01,,0,0.1,0,0,10,0,0.02,3\n"
                                      "0.02,100,0,abc,0,0,10,0,0.02,3\n"
                                      "0.03,100,0,0.1\n"
                                      "0.03,nan,0,0.1,0,0,10,0,0.02,3\n"
                                      "0.02,100,0,0.1,0,0,10,0,0.02,3\n");
  SamplesCsvReader reader(path);
  ASSERT_EQ(reader.error(), "");
  auto a = reader.next();
  ASSERT_TRUE(a);
  EXPECT_TRUE(a->has(Input::kWheelTorque));
  EXPECT_EQ(a->gear, 3);
  auto b = reader.next();
  ASSERT_TRUE(b);
  EXPECT_FALSE(b->has(Input::kWheelTorque));
  EXPECT_TRUE(b->has(Input::kAccelX));
  auto c = reader.next();  // the nan row: torque invalid
  ASSERT_TRUE(c);
  EXPECT_EQ(c->time_us, 30'000);
  EXPECT_FALSE(c->has(Input::kWheelTorque));
  EXPECT_FALSE(reader.next());  // 0.02 after 0.03: time does not increase
  EXPECT_EQ(reader.skipped_rows(), 3);
  ASSERT_EQ(reader.warnings().size(), 3u);
  EXPECT_EQ(reader.warnings()[0], path + ":4: accel_x_mps2 is not a number: 'abc'");
  EXPECT_EQ(reader.warnings()[1], path + ":5: expected 10 cells, got 4");
  EXPECT_EQ(reader.warnings()[2], path + ":7: time_s does not increase");
  std::remove(path.c_str());
}

TEST(SamplesCsv, MissingFileAndHeader) {
  SamplesCsvReader missing("/nonexistent/samples.csv");
  EXPECT_EQ(missing.error(),
            "/nonexistent/samples.csv: cannot open the samples file: No such file or directory");
  const std::string path = write_temp("a,b\n1,2\n");
  SamplesCsvReader no_time(path);
  EXPECT_EQ(no_time.error(), path + ":1: the header has no time_s column");
  std::remove(path.c_str());
}

}  // namespace
}  // namespace vmass
