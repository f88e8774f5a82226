#include "vmass/io/regular_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>

namespace vmass::io {
namespace {

/// "is a directory", "is a FIFO", ... for a file that is not regular.
std::string kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "is a directory";
  if (S_ISFIFO(mode)) return "is a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "is a character device";
  if (S_ISBLK(mode)) return "is a block device";
  if (S_ISSOCK(mode)) return "is a socket";
  return "is not a regular file";
}

/// Closes the descriptor when it goes out of scope.
struct Fd {
  int fd = -1;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

FileText read_regular_file(const std::string& path, std::size_t max_bytes, std::string_view what) {
  FileText out;
  const std::string prefix = path + ": cannot read the " + std::string(what) + ": ";
  // O_NONBLOCK: opening a FIFO must not wait for a writer (it is refused just below).
  Fd f{::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY)};
  if (f.fd < 0) {
    out.error = path + ": cannot open the " + std::string(what) + ": " + std::strerror(errno);
    out.missing = errno == ENOENT;
    return out;
  }
  struct stat st {};
  if (::fstat(f.fd, &st) != 0) {
    out.error = prefix + std::strerror(errno);
    return out;
  }
  if (!S_ISREG(st.st_mode)) {
    out.error = prefix + kind_of(st.st_mode);
    return out;
  }
  if (static_cast<std::uint64_t>(st.st_size) > max_bytes) {
    out.error = prefix + "larger than " + std::to_string(max_bytes >> 20) + " MiB";
    return out;
  }
  std::string text;
  char buf[64 * 1024];
  for (;;) {
    const ssize_t n = ::read(f.fd, buf, sizeof buf);
    if (n < 0) {
      if (errno == EINTR) continue;
      out.error = prefix + "read error: " + std::strerror(errno);
      return out;
    }
    if (n == 0) break;
    if (text.size() + static_cast<std::size_t>(n) > max_bytes) {  // grew while we read
      out.error = prefix + "larger than " + std::to_string(max_bytes >> 20) + " MiB";
      return out;
    }
    text.append(buf, static_cast<std::size_t>(n));
  }
  out.text = std::move(text);
  return out;
}

std::string check_input_file(const std::string& path, bool allow_fifo) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return std::strerror(errno);
  if (S_ISREG(st.st_mode) || (allow_fifo && S_ISFIFO(st.st_mode))) return "";
  return kind_of(st.st_mode);
}

std::unique_ptr<std::ifstream> open_input_stream(const std::string& path, std::string_view what,
                                                 std::string* error) {
  std::string why = check_input_file(path, true);
  auto file = why.empty() ? std::make_unique<std::ifstream>(path, std::ios::binary) : nullptr;
  if (file && !*file) why = std::strerror(errno);
  if (why.empty()) return file;
  if (error) *error = path + ": cannot open the " + std::string(what) + ": " + why;
  return nullptr;
}

}  // namespace vmass::io
