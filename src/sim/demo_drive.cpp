#include "vmass/sim/demo_drive.hpp"

#include <memory>
#include <string>
#include <utility>

#include "vmass/sim/can_writer.hpp"
#include "vmass/sim/config_writer.hpp"
#include "vmass/sim/static_ballast.hpp"

namespace vmass::sim {

namespace {

class DemoTeam final : public VehicleTeam {
 public:
  explicit DemoTeam(bool ballast_test) : ballast_test_(ballast_test) {}

  std::string hand_over(const SimulationResult& result, Handover* out) const override {
    out->dbc_text = std::string(demo_vehicle_dbc());
    if (auto m = make_can_frames(result, &out->frames); !m.empty()) return m;
    out->config_yaml = demo_config_yaml(result) + demo_can_config_yaml("vehicle.dbc");
    out->extra_files.clear();
    if (!ballast_test_) return "";
    const BallastSchedule schedule;
    if (auto m = schedule.validate(); !m.empty()) return m;
    out->extra_files = {{"ballast.csv", ballast_csv(result, schedule)},
                        {"suspension_truth.yaml", suspension_truth_yaml(result, schedule)}};
    return "";
  }

 private:
  bool ballast_test_;
};

}  // namespace

std::optional<DriveSpec> demo_drive(std::string_view scenario) {
  std::optional<Scenario> found = find_scenario(scenario);
  if (!found) return std::nullopt;
  DriveSpec drive;
  drive.scenario = std::move(*found);
  // The ballast test's team also hands over what vmass-calibrate reads.
  drive.team = std::make_shared<DemoTeam>(scenario == "static_ballast");
  return drive;
}

}  // namespace vmass::sim
