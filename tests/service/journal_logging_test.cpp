// journal_line(): the sd-daemon(3) form of a log message (priority prefix, one line).
#include <gtest/gtest.h>

#include "vmass/service/journal_logging.hpp"

namespace vmass::service {
namespace {

TEST(JournalLine, PriorityPrefixAndOneLine) {
  EXPECT_EQ(journal_line(3, "cannot open LCM"), "<3>cannot open LCM\n");
  EXPECT_EQ(journal_line(4, "not mapped"), "<4>not mapped\n");
  EXPECT_EQ(journal_line(6, "can.inputs:\nspeed <- A.B\ngear <- C.D\n"),
            "<6>can.inputs:; speed <- A.B; gear <- C.D\n");
  EXPECT_EQ(journal_line(7, "crlf\r\nline"), "<7>crlf; line\n");
}

}  // namespace
}  // namespace vmass::service
