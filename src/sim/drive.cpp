#include "vmass/sim/drive.hpp"

#include <sstream>

#include "text_file.hpp"
#include "vmass/can/candump.hpp"
#include "vmass/sim/csv_writer.hpp"

namespace vmass::sim {

std::string record_drive(const DriveSpec& drive, DriveOutput* out) {
  if (auto m = simulate(drive.scenario, drive.options, &out->result); !m.empty()) return m;
  return drive.team->hand_over(out->result, &out->handover);
}

std::string candump_text(const std::vector<can::CanFrame>& frames) {
  std::ostringstream log;
  can::CandumpWriter writer(log);
  for (const can::CanFrame& f : frames) writer.write(f, "can0");
  return log.str();
}

std::string write_drive_files(const DriveOutput& drive, const std::string& dir) {
  const Handover& h = drive.handover;
  if (auto m = write_csv_files(drive.result, dir); !m.empty()) return m;
  const TextFile files[] = {{"config.yaml", h.config_yaml},
                            {"vehicle.dbc", h.dbc_text},
                            {"drive.log", candump_text(h.frames)}};
  for (const TextFile& f : files) {
    if (auto m = detail::write_text_file(dir + "/" + f.name, f.text); !m.empty()) return m;
  }
  for (const TextFile& f : h.extra_files) {
    if (auto m = detail::write_text_file(dir + "/" + f.name, f.text); !m.empty()) return m;
  }
  return "";
}

}  // namespace vmass::sim
