// Reading files that come from many hands, bounded: whatever a path names (a directory, a FIFO,
// /dev/zero, a 50 GB file), a reader gets either the text it expects or an error that names the
// path and says why, never a hang and never an unbounded allocation.
//
//   read_regular_file(path, max_bytes, what)   the whole of a regular file of at most
//                                              max_bytes; opened with O_NONBLOCK, so that a FIFO
//                                              cannot block the caller; read errors are errors,
//                                              never taken for the end of the file
//   check_input_file(path, allow_fifo)         "" when path names a regular file (or, when
//                                              allowed, a FIFO or pipe, e.g. /dev/stdin), else
//                                              why not ("is a directory", "is a character
//                                              device", ...)
//   open_input_stream(path, what, error)       a stream on a file check_input_file accepts
//                                              (FIFOs too), or null and "path: cannot open
//                                              the <what>: why"
//
// Thread-safety: reentrant free functions (system calls only).
#pragma once

#include <cstddef>
#include <fstream>
#include <memory>
#include <string>
#include <string_view>

namespace vmass::io {

/// Size bounds of the files vmass reads whole (far above any real one, far below memory).
constexpr std::size_t kMaxConfigBytes = 4u << 20;   ///< config.yaml
constexpr std::size_t kMaxDbcBytes = 64u << 20;     ///< a DBC (real ones are below 10 MB)
constexpr std::size_t kMaxStateBytes = 1u << 20;    ///< the daemon's state file
constexpr std::size_t kMaxTableBytes = 256u << 20;  ///< a CSV read whole (ballast, truth)
constexpr std::size_t kMaxListBytes = 16u << 20;    ///< a list of paths (vmass-replay --log-list)

struct FileText {
  std::string text;
  std::string error;     ///< "path: cannot open|read the <what>: why"; text is then empty
  bool missing = false;  ///< the path names nothing (ENOENT)
  bool ok() const { return error.empty(); }
};

/// Reads a regular file whole (see the header comment). `what` names the file's role in errors
/// ("config", "DBC", ...): "drive.dbc: cannot read the DBC: is a directory",
/// "x.yaml: cannot open the config: No such file or directory".
FileText read_regular_file(const std::string& path, std::size_t max_bytes, std::string_view what);

/// "" when path can be opened for streaming input, else why not (see the header comment).
std::string check_input_file(const std::string& path, bool allow_fifo);

/// A binary input stream on path, a regular file or a FIFO (a log read as it streams); null and
/// *error "path: cannot open the <what>: why" otherwise.
std::unique_ptr<std::ifstream> open_input_stream(const std::string& path, std::string_view what,
                                                 std::string* error);

}  // namespace vmass::io
