// The exit-code convention of every vmass tool, and the command-line parse that follows it.
//
//   0  ok (and --help)
//   1  failure: the run started and did not complete (write or plot failure, a fit that is not
//      usable, a device lost, nothing arrived before a timeout)
//   2  usage or input error: a bad or missing option, a file that cannot be read or does not
//      parse, an invalid configuration
//
// CLI11's own codes (106 for a missing required option, ...) never reach the shell. Tested per
// tool in tests/tools. The parse also gives every tool `--version` ("vmass-replay 0.1.0", the
// version of vmass/version.hpp), which help2man reads for the man pages.
#pragma once

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "vmass/version.hpp"

namespace vmass::tools {

enum ExitCode : int { kExitOk = 0, kExitFailure = 1, kExitUsage = 2 };

/// "NAME VERSION" for --version; NAME is argv[0] without its directory.
inline std::string version_line(const char* argv0) {
  std::string name = argv0 != nullptr ? argv0 : "vmass";
  name = name.substr(name.find_last_of('/') + 1);
  return name + " " + kVersion;
}

/// Parses the command line. nullopt: go on; otherwise return this code from main (0 after
/// --help or --version, kExitUsage after a parse error; CLI11 has printed the message).
inline std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv) {
  app.set_version_flag("--version", version_line(argc > 0 ? argv[0] : nullptr),
                       "print the program's name and version, then exit");
  try {
    app.parse(argc, argv);
    return std::nullopt;
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kExitOk : kExitUsage;
  }
}

}  // namespace vmass::tools
