#include "vmass/sim/population_writer.hpp"

#include <sstream>

#include "text_file.hpp"
#include "vmass/can/candump.hpp"
#include "vmass/sim/csv_writer.hpp"
#include "vmass/sim/vehicle_bus.hpp"

namespace vmass::sim {

std::string simulate_population_run(const DrawnVehicle& vehicle, const PopulationRun& run,
                                    Knowledge knowledge, SimulationResult* result,
                                    std::vector<can::CanFrame>* frames) {
  SimulationOptions options;
  options.seed = run.bus.seed;
  options.realism = run.realism;
  options.record_ecu_trace = true;
  if (auto m = simulate(run.physics, options, result); !m.empty()) return m;
  BusOptions bus = run.bus;
  bus.torque_report_scale *= torque_report_scale(vehicle, knowledge);
  const VehicleBus vehicle_bus(vehicle);
  return vehicle_bus.encode(*result, bus, frames);
}

std::string candump_text(const std::vector<can::CanFrame>& frames) {
  std::ostringstream log;
  can::CandumpWriter writer(log);
  for (const can::CanFrame& f : frames) writer.write(f, "can0");
  return log.str();
}

std::string write_population_files(const DrawnVehicle& vehicle, const PopulationRun& run,
                                   Knowledge knowledge, const SimulationResult& result,
                                   const std::vector<can::CanFrame>& frames,
                                   const std::string& dir) {
  const VehicleBus bus(vehicle);
  if (!bus.error().empty()) return vehicle.id + ": " + bus.error();
  if (auto m = detail::write_text_file(dir + "/vehicle.dbc", bus.dbc_text()); !m.empty()) return m;
  if (auto m = detail::write_text_file(dir + "/drive.log", candump_text(frames)); !m.empty()) {
    return m;
  }
  const std::string config = datasheet_config_yaml(vehicle, run.realism, knowledge, "vehicle.dbc");
  if (auto m = detail::write_text_file(dir + "/config.yaml", config); !m.empty()) return m;
  return write_csv_files(result, dir);
}

}  // namespace vmass::sim
