// Private helper of the sim writers: write a whole text file, reporting failures as messages.
#pragma once

#include <string>

namespace vmass::sim::detail {

/// Writes content to path (truncating). "" or "cannot write PATH: reason".
std::string write_text_file(const std::string& path, const std::string& content);

}  // namespace vmass::sim::detail
