#include "text_file.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>

namespace vmass::sim::detail {

std::string write_text_file(const std::string& path, const std::string& content) {
  errno = 0;
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  if (!f) {
    return "cannot write " + path + ": " + (errno != 0 ? std::strerror(errno) : "open failed");
  }
  f.write(content.data(), static_cast<std::streamsize>(content.size()));
  f.close();
  if (!f) return "cannot write " + path + ": write failed";
  return "";
}

}  // namespace vmass::sim::detail
