// Minimal CSV helpers for our own numeric files: comma-separated, no quoting (our files never
// quote), locale-free numbers.
#pragma once

#include <string>
#include <vector>

namespace vmass {

std::vector<std::string> split_csv_line(const std::string& line);
/// Locale-free; the whole cell must be a number (surrounding spaces allowed).
bool parse_csv_number(const std::string& cell, double* out);

}  // namespace vmass
