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

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
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

namespace detail {
inline std::string& program_name() {
  static std::string name = "vmass";
  return name;
}
/// At exit: the standard output flushed, and a write that failed (a full disk, /dev/full, a
/// closed pipe) is exit status 1 with a message, whatever main returned: a summary or a CSV
/// cut short is never a success.
inline void check_standard_output() {
  if (std::fflush(stdout) == 0 && !std::ferror(stdout)) return;
  const int error = errno;
  std::fprintf(stderr, "%s: cannot write the standard output: %s\n", program_name().c_str(),
               error != 0 ? std::strerror(error) : "write error");
  std::_Exit(kExitFailure);
}
}  // namespace detail

/// Makes a failed write of the standard output the tool's failure (see
/// detail::check_standard_output); parse_command_line() calls it.
inline void check_standard_output_at_exit(const char* argv0) {
  static bool registered = false;
  if (registered) return;
  registered = true;
  const std::string name = argv0 != nullptr ? argv0 : "vmass";
  detail::program_name() = name.substr(name.find_last_of('/') + 1);
  std::atexit(detail::check_standard_output);
}

/// Parses the command line. nullopt: go on; otherwise return this code from main (0 after
/// --help or --version, kExitUsage after a parse error; CLI11 has printed the message).
inline std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv) {
  check_standard_output_at_exit(argc > 0 ? argv[0] : nullptr);
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
