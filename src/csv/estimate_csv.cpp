#include "vmass/csv/estimate_csv.hpp"

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
  // Before the first estimate (no prior yet) the belief cells are empty: a 0 there would read
  // as an estimate of 0 kg.
  char mass[160] = ",,,";
  char std_kg[32] = "";
  char initial[32] = "";
  if (e.has_mass()) {
    std::snprintf(mass, sizeof mass, "%.3f,%.3f,%.3f,%.3f", e.mass_kg, e.ci_low_kg, e.ci_high_kg,
                  e.mu_n);
    std::snprintf(std_kg, sizeof std_kg, "%.3f", e.mass_std_kg);
    std::snprintf(initial, sizeof initial, "%.3f", e.initial_mass_kg);
  }
  char buf[512];
  std::snprintf(buf, sizeof buf, "%.2f,%s,%s,%s,%s,%ld,%ld,%.5f,%.5f,%s", to_seconds(e.time_us),
                mass, std::string(status_name(e.status)).c_str(), std_kg,
                std::string(reason_name(e.reason)).c_str(), e.blocks[0].accepted,
                e.blocks[1].accepted, e.blocks[0].availability(), e.blocks[1].availability(),
                initial);
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
