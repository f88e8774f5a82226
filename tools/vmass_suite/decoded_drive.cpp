#include "decoded_drive.hpp"

#include <fstream>
#include <utility>

#include "vmass/runtime/can_input_source.hpp"
#include "vmass/runtime/candump_frame_source.hpp"
#include "vmass/runtime/tick_driver.hpp"
#include "vmass/signals/signal_mapping.hpp"

namespace vmass::suite {

std::string write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  out.close();
  return out ? "" : "cannot write " + path;
}

std::string without_dir(std::string message, const std::string& dir) {
  const std::string prefix = dir + "/";
  for (std::size_t at = message.find(prefix); at != std::string::npos; at = message.find(prefix)) {
    message.erase(at, prefix.size());
  }
  return message;
}

DecodedDrive decode_drive(const sim::VehicleTeam& team, const sim::SimulationResult& result,
                          const DecodeOptions& options, const std::string& work_dir) {
  DecodedDrive out;
  sim::Handover handover;
  if (auto m = team.hand_over(result, &handover); !m.empty()) {
    out.error = "bus: " + m;
    return out;
  }
  for (can::CanFrame& f : handover.frames) f.time_us += options.time_offset_us;
  std::string yaml = handover.config_yaml;
  if (!options.estimator_yaml.empty()) yaml += "\n" + options.estimator_yaml + "\n";
  out.config_path = work_dir + "/config.yaml";
  if (auto m = write_file(work_dir + "/vehicle.dbc", handover.dbc_text); !m.empty()) {
    out.error = m;
    return out;
  }
  if (auto m = write_file(out.config_path, yaml); !m.empty()) {
    out.error = m;
    return out;
  }
  ConfigLoad loaded = load_config(out.config_path);
  if (!loaded.ok()) {
    out.error = loaded.error;
    return out;
  }
  signals::CanInputsLoad can = signals::load_can_inputs(*loaded.config);
  if (!can.ok()) {
    out.error = can.error;
    return out;
  }
  std::string text = sim::candump_text(handover.frames);
  if (options.keep_log_text) out.log_text = text;
  runtime::CanInputSource source(
      runtime::CandumpFrameSource::from_text(std::move(text), "drive.log"), can.inputs->decoder,
      can.inputs->mapping);
  out.samples.reserve(result.truth.size() + 16);
  runtime::UnpacedClock clock;
  runtime::TickDriver(source, loaded.config->pipeline.estimator.differencing.tick_rate_hz)
      .run(clock, [&](std::int64_t, TimeUs t) { out.samples.push_back(source.sample_at(t)); });
  out.config = std::move(loaded.config);
  return out;
}

}  // namespace vmass::suite
