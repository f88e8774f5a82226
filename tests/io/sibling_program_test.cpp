// The programs shipped beside the executables: found in the running executable's folder, else
// left to PATH; a shell-quoted word reaches the program as it was, whatever it holds.
#include "vmass/io/sibling_program.hpp"

#include <cstdio>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

namespace vmass::io {
namespace {

/// What /bin/sh makes of `printf %s WORD`.
std::string printed_by_shell(const std::string& word) {
  const std::string command = "printf %s " + word;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return "<popen failed>";
  std::string out;
  char buf[256];
  for (std::size_t n = 0; (n = std::fread(buf, 1, sizeof buf, pipe)) > 0;) out.append(buf, n);
  ::pclose(pipe);
  return out;
}

TEST(SiblingProgram, AProgramBesideTheExecutableIsNamedByItsPath) {
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe");
  const std::string name = self.filename().string();  // this test's own executable
  EXPECT_EQ(sibling_program(name), self.string());
}

TEST(SiblingProgram, AProgramNotBesideItIsLeftToPath) {
  EXPECT_EQ(sibling_program("vmass-no-such-program"), "vmass-no-such-program");
}

TEST(ShellQuote, OneWordWhateverItHolds) {
  EXPECT_EQ(shell_quote("plain"), "'plain'");
  EXPECT_EQ(shell_quote("it's"), "'it'\\''s'");
  for (const std::string s : {"", "two words", "it's", "''", "$HOME `id` $(id) \\n *", "a\nb"}) {
    EXPECT_EQ(printed_by_shell(shell_quote(s)), s) << s;
  }
}

}  // namespace
}  // namespace vmass::io
