// Drive: the simulator's one front end. A drive is a vehicle with its load on a road with a
// driver (Scenario), how it is simulated (SimulationOptions), and its vehicle team: the one
// that owns the vehicle's CAN bus and writes its config from what its engineer knows
// (VehicleTeam). The demo car's named scenarios (demo_drive.hpp) and the population's vehicles
// (population_drive.hpp) are two ways of filling one in; both are recorded and written here:
//
//   DIR/samples.csv, DIR/truth.csv   the simulator's samples and hidden truth (csv_writer.hpp)
//   DIR/vehicle.dbc                  the vehicle's DBC
//   DIR/drive.log                    its bus during the drive (candump -l, interface can0)
//   DIR/config.yaml                  its config, the `can:` section mapping vehicle.dbc
//   DIR/...                          any other file the team hands over (the ballast test's)
//
// Thread-safe on distinct drives and directories (a VehicleTeam is immutable).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "vmass/can/can_frame.hpp"
#include "vmass/sim/scenario.hpp"
#include "vmass/sim/simulator.hpp"

namespace vmass::sim {

struct TextFile {
  std::string name;  ///< in the output directory
  std::string text;
};

/// What a vehicle team hands over with a simulated drive, besides the truth.
struct Handover {
  std::string dbc_text;
  std::vector<can::CanFrame> frames;  ///< in time order
  std::string config_yaml;            ///< its `can:` section maps the DBC as "vehicle.dbc"
  std::vector<TextFile> extra_files;
};

/// The team of one vehicle: its bus and its engineer.
class VehicleTeam {
 public:
  virtual ~VehicleTeam() = default;
  /// The DBC, the frames its ECUs sent during the drive and the config. "" or a message.
  virtual std::string hand_over(const SimulationResult& result, Handover* out) const = 0;
};

/// A vehicle + a drive + what its engineer knows.
struct DriveSpec {
  Scenario scenario;
  SimulationOptions options;
  std::shared_ptr<const VehicleTeam> team;
};

struct DriveOutput {
  SimulationResult result;
  Handover handover;
};

/// Simulates the drive and takes its team's handover. "" or a message.
std::string record_drive(const DriveSpec& drive, DriveOutput* out);

/// candump -l text of frames on interface can0.
std::string candump_text(const std::vector<can::CanFrame>& frames);

/// Writes the drive's files into DIR (which must exist). "" or a message naming the file.
std::string write_drive_files(const DriveOutput& drive, const std::string& dir);

}  // namespace vmass::sim
