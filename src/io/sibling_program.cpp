#include "vmass/io/sibling_program.hpp"

#include <filesystem>
#include <system_error>

namespace vmass::io {

std::string sibling_program(const std::string& name) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path beside = self.parent_path() / name;
    if (fs::exists(beside, ec)) return beside.string();
  }
  return name;  // on PATH
}

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (const char c : s) {
    if (c == '\'') {
      out += "'\\''";  // close the quote, an escaped quote, open again
    } else {
      out += c;
    }
  }
  return out + "'";
}

}  // namespace vmass::io
