// The programs vmass ships beside its executables (vmass-plot, vmass-calibrate-plot,
// vmass-log-convert: build/bin, or the install's bin), and the shell command line that runs
// one:
//     sibling_program("vmass-plot")   -> /usr/bin/vmass-plot (beside /proc/self/exe), else
//                                        "vmass-plot" (found on PATH when run)
//     shell_quote("it's")             -> 'it'\''s'   (one word for /bin/sh, whatever it holds)
//
// Thread-safety: reentrant.
#pragma once

#include <string>

namespace vmass::io {

/// The program `name` in the folder of the running executable when it is there, else `name`
/// alone (the shell or posix_spawnp looks it up on PATH).
std::string sibling_program(const std::string& name);

/// `s` as one single-quoted word of a /bin/sh command line.
std::string shell_quote(const std::string& s);

}  // namespace vmass::io
