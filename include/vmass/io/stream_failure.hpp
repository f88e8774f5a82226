// The reason of a stream's read failure, as the readers report it: libstdc++ carries the
// read's errno in the exception's code (system or generic category); else its what().
// Header only, so that the small readers (the BLF reader's fuzz target) need no library.
#pragma once

#include <cstring>
#include <ios>
#include <string>
#include <system_error>

namespace vmass::io {

inline std::string read_failure(const std::ios_base::failure& e) {
  const std::error_code& code = e.code();
  const bool is_errno =
      code.category() == std::system_category() || code.category() == std::generic_category();
  return code.value() > 0 && is_errno ? std::strerror(code.value()) : e.what();
}

}  // namespace vmass::io
