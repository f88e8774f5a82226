// The simulator's one front end (drive.hpp) on the demo car: a named scenario becomes a drive
// whose team hands over the demo DBC, its frames and the config with its `can:` section, the
// ballast test its two extra files; the files are written where the drive says.
#include <gtest/gtest.h>

#include <filesystem>

#include "sim_test_util.hpp"
#include "vmass/sim/can_writer.hpp"
#include "vmass/sim/config_writer.hpp"
#include "vmass/sim/demo_drive.hpp"
#include "vmass/sim/drive.hpp"

namespace vmass::sim {
namespace {

namespace fs = std::filesystem;

TEST(SimDrive, ADemoScenarioIsADriveOfTheDemoTeam) {
  EXPECT_FALSE(demo_drive("paper_exp3").has_value());
  std::optional<DriveSpec> spec = demo_drive("steady_turn");
  ASSERT_TRUE(spec.has_value());
  spec->options = test::ideal();
  DriveOutput drive;
  ASSERT_EQ(record_drive(*spec, &drive), "");
  const Handover& h = drive.handover;
  EXPECT_EQ(h.dbc_text, std::string(demo_vehicle_dbc()));
  EXPECT_GT(h.frames.size(), drive.result.samples.size());
  EXPECT_EQ(h.config_yaml, demo_config_yaml(drive.result) + demo_can_config_yaml("vehicle.dbc"));
  EXPECT_TRUE(h.extra_files.empty());
}

TEST(SimDrive, TheBallastTestHandsOverItsTwoFilesAndEveryFileIsWritten) {
  std::optional<DriveSpec> spec = demo_drive("static_ballast");
  ASSERT_TRUE(spec.has_value());
  DriveOutput drive;
  ASSERT_EQ(record_drive(*spec, &drive), "");
  ASSERT_EQ(drive.handover.extra_files.size(), 2u);
  const fs::path dir = fs::temp_directory_path() / "vmass_sim_drive_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  ASSERT_EQ(write_drive_files(drive, dir.string()), "");
  for (const char* name : {"samples.csv", "truth.csv", "config.yaml", "vehicle.dbc", "drive.log",
                           "ballast.csv", "suspension_truth.yaml"}) {
    EXPECT_GT(fs::file_size(dir / name), 100u) << name;
  }
  EXPECT_EQ(test::read_file((dir / "drive.log").string()), candump_text(drive.handover.frames));
  fs::remove_all(dir);
  EXPECT_NE(write_drive_files(drive, "/nonexistent_vmass_dir").find("/nonexistent_vmass_dir/"),
            std::string::npos);
}

}  // namespace
}  // namespace vmass::sim
