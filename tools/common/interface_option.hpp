// --interface NAME: one interface of a multi-interface CAN log, the same option in every tool
// that reads a log (runtime/interface_selection.hpp). A name no interface can have is a usage
// error (exit 2, tools/common/exit_code.hpp); a name the log does not have is found out while
// reading it.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "vmass/runtime/interface_selection.hpp"

namespace vmass::tools {

inline CLI::Option* add_interface_option(CLI::App& app, std::string* name) {
  const CLI::Validator interface_name(
      [](std::string& s) { return runtime::InterfaceSelection::name_error(s); }, "NAME");
  return app
      .add_option("--interface", *name,
                  "read one interface of a multi-interface CAN log, its frames only (the "
                  "others are skipped and counted): candump -l's interface name, can<N-1> for "
                  "ASC, TRC, BLF channel N and MDF4 bus N")
      ->check(interface_name);
}

}  // namespace vmass::tools
