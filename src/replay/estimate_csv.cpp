#include "vmass/replay/estimate_csv.hpp"

namespace vmass {

EstimateCsvWriter::EstimateCsvWriter(const std::string& path) {
  file_ = std::fopen(path.c_str(), "w");
  if (file_ && std::fputs((header() + "\n").c_str(), file_) < 0) failed_ = true;
}

EstimateCsvWriter::~EstimateCsvWriter() { close(); }

std::string EstimateCsvWriter::header() {
  return "time_s,mass_kg,mass_ci_low_kg,mass_ci_high_kg,mu_n,status,mass_std_kg,reason,"
         "longitudinal_pairs,lateral_pairs,longitudinal_availability,lateral_availability,"
         "initial_mass_kg";
}

std::string EstimateCsvWriter::row(const Estimate& e) {
  // %.*f is locale-dependent only through LC_NUMERIC, which our tools never change from "C".
  char buf[512];
  std::snprintf(buf, sizeof buf, "%.2f,%.3f,%.3f,%.3f,%.3f,%s,%.3f,%s,%ld,%ld,%.5f,%.5f,%.3f",
                to_seconds(e.time_us), e.mass_kg, e.ci_low_kg, e.ci_high_kg, e.mu_n,
                std::string(status_name(e.status)).c_str(), e.mass_std_kg,
                std::string(reason_name(e.reason)).c_str(), e.blocks[0].accepted,
                e.blocks[1].accepted, e.blocks[0].availability(), e.blocks[1].availability(),
                e.initial_mass_kg);
  return buf;
}

void EstimateCsvWriter::write(const Estimate& e) {
  if (!file_) return;
  const std::string line = row(e) + "\n";
  if (std::fputs(line.c_str(), file_) < 0) failed_ = true;
}

bool EstimateCsvWriter::close() {
  if (!file_) return !failed_;
  if (std::fclose(file_) != 0) failed_ = true;
  file_ = nullptr;
  return !failed_;
}

}  // namespace vmass
