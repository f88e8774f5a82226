#include "vmass/csv/csv.hpp"

#include <limits>
#include <locale>
#include <sstream>

namespace vmass {

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  for (char ch : line) {
    if (ch == ',') {
      cells.push_back(cell);
      cell.clear();
    } else if (ch != '\r') {
      cell.push_back(ch);
    }
  }
  cells.push_back(cell);
  for (auto& c : cells) {
    const auto b = c.find_first_not_of(' ');
    const auto e = c.find_last_not_of(' ');
    c = b == std::string::npos ? std::string() : c.substr(b, e - b + 1);
  }
  return cells;
}

bool parse_csv_number(const std::string& cell, double* out) {
  if (cell == "nan" || cell == "NaN") {
    *out = std::numeric_limits<double>::quiet_NaN();
    return true;
  }
  std::istringstream in(cell);
  in.imbue(std::locale::classic());
  double v = 0.0;
  in >> v;
  if (in.fail()) return false;
  in >> std::ws;
  if (!in.eof()) return false;
  *out = v;
  return true;
}

}  // namespace vmass
