#include "fleet_table.hpp"

#include <array>
#include <utility>
#include <vector>

#include "vmass/csv/fixed_decimal.hpp"
#include "vmass/json/json.hpp"

namespace vmass {
namespace {

/// A cell: its CSV text and its JSON value (null when empty; a number reads back as the text).
struct Cell {
  std::string text;
  json::Json value;
};

std::string fixed(double v, int decimals) {
  char buf[kMaxFixedChars];
  return std::string(buf, write_fixed(buf, buf + sizeof buf, v, decimals));
}

Cell number(double v, int decimals, bool present = true) {
  if (!present) return {};
  return {fixed(v, decimals), json::fixed(v, decimals)};
}
Cell count(long v) { return {std::to_string(v), v}; }
Cell text(std::string_view v) { return {std::string(v), std::string(v)}; }

constexpr std::array<const char*, 21> kColumns = {"log",
                                                  "frames",
                                                  "corrupt_lines",
                                                  "duration_s",
                                                  "ticks",
                                                  "estimator",
                                                  "status",
                                                  "reason",
                                                  "mass_kg",
                                                  "mass_ci_low_kg",
                                                  "mass_ci_high_kg",
                                                  "mass_std_kg",
                                                  "mu_n",
                                                  "initial_mass_kg",
                                                  "prior",
                                                  "pairs_used",
                                                  "pairs_accepted",
                                                  "longitudinal_availability",
                                                  "lateral_availability",
                                                  "reinitialisations",
                                                  "error"};

std::vector<Cell> cells(const FleetLogResult& r) {
  std::vector<Cell> c(kColumns.size());
  c.front() = text(r.path);
  c.back() = r.error.empty() ? Cell() : text(r.error);    // JSON null when there is none
  if (!r.error.empty() && r.estimator.empty()) return c;  // not replayed: path and error only
  const scoring::ReplaySummary::Result& s = r.summary;
  const Estimate& e = s.final_estimate;
  const bool mass = s.has_estimate;
  c[1] = count(static_cast<long>(r.frames));
  c[2] = count(static_cast<long>(r.corrupt_lines));
  c[3] = number(s.duration_s, 2);
  c[4] = count(s.ticks);
  c[5] = text(r.estimator);
  c[6] = text(status_name(e.status));
  c[7] = text(reason_name(e.reason));
  const double masses[] = {e.mass_kg,     e.ci_low_kg, e.ci_high_kg,
                           e.mass_std_kg, e.mu_n,      e.initial_mass_kg};
  for (std::size_t i = 0; i < 6; ++i) c[8 + i] = number(masses[i], 3, mass);
  c[14] = text(mass ? reason_name(e.prior_reason) : std::string_view());
  c[15] = count(e.pairs_used);
  c[16] = count(s.pairs_accepted);
  c[17] = number(e.blocks[0].availability(), 5);
  c[18] = number(e.blocks[1].availability(), 5);
  c[19] = count(s.reinitialisations);
  return c;
}

std::string csv_cell(const Cell& cell) {
  if (cell.text.find_first_of(",\"\n\r") == std::string::npos) return cell.text;
  std::string out = "\"";
  for (char ch : cell.text) out += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return out + "\"";
}

}  // namespace

std::string fleet_csv_header() {
  std::string out;
  for (const char* column : kColumns) out += (out.empty() ? "" : ",") + std::string(column);
  return out + "\n";
}

std::string fleet_csv_row(const FleetLogResult& r) {
  std::string out;
  const std::vector<Cell> c = cells(r);
  for (std::size_t i = 0; i < c.size(); ++i) out += (i == 0 ? "" : ",") + csv_cell(c[i]);
  return out + "\n";
}

std::string fleet_json_line(const FleetLogResult& r) {
  json::Json j;
  const std::vector<Cell> c = cells(r);
  for (std::size_t i = 0; i < c.size(); ++i) j[kColumns[i]] = c[i].value;
  return json::dump(j) + "\n";
}

}  // namespace vmass
