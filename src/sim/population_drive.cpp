#include "vmass/sim/population_drive.hpp"

#include <string>

#include "vmass/sim/vehicle_bus.hpp"

namespace vmass::sim {

namespace {

class PopulationTeam final : public VehicleTeam {
 public:
  PopulationTeam(const DrawnVehicle& vehicle, const PopulationRun& run, Knowledge knowledge)
      : vehicle_(vehicle), bus_(run.bus), realism_(run.simulation.realism), knowledge_(knowledge) {
    bus_.torque_report_scale *= torque_report_scale(vehicle, knowledge);
  }

  std::string hand_over(const SimulationResult& result, Handover* out) const override {
    const VehicleBus bus(vehicle_);
    if (auto m = bus.encode(result, bus_, &out->frames); !m.empty()) return m;
    out->dbc_text = bus.dbc_text();
    out->config_yaml = datasheet_config_yaml(vehicle_, realism_, knowledge_, "vehicle.dbc");
    out->extra_files.clear();
    return "";
  }

 private:
  DrawnVehicle vehicle_;
  BusOptions bus_;  ///< the run's, with the knowledge's torque scale
  Realism realism_;
  Knowledge knowledge_;
};

}  // namespace

std::shared_ptr<const VehicleTeam> population_team(const DrawnVehicle& vehicle,
                                                   const PopulationRun& run, Knowledge knowledge) {
  return std::make_shared<PopulationTeam>(vehicle, run, knowledge);
}

DriveSpec population_drive(const DrawnVehicle& vehicle, const PopulationRun& run,
                           Knowledge knowledge) {
  DriveSpec drive;
  drive.scenario = run.physics;
  drive.options = run.simulation;
  drive.team = population_team(vehicle, run, knowledge);
  return drive;
}

}  // namespace vmass::sim
