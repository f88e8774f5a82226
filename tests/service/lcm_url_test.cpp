// An LCM URL is a configuration: a provider liblcm does not have, an option it would ignore, a
// unicast address for udpm are refused before LCM opens anything (vmassd: exit 2, not a restart
// loop); what liblcm itself accepts passes.
#include "vmass/service/lcm_url.hpp"

#include <gtest/gtest.h>

namespace vmass::service {
namespace {

TEST(LcmUrl, WhatLiblcmTakesPasses) {
  for (const char* url : {"udpm://239.255.76.67:7667?ttl=0", "udpm://239.255.76.67:7667", "udpm://",
                          "udpm://239.255.76.67:7667?ttl=1&recv_buf_size=2097152", "memq://",
                          "file:///tmp/run.lcm?mode=w", "file://run.lcm?mode=a&speed=2",
                          "tcpq://127.0.0.1:7700", "mpudpm://239.255.76.67:7667?ttl=0"}) {
    EXPECT_EQ(lcm_url_error(url), "") << url;
  }
}

TEST(LcmUrl, EachMistakeSaysWhat) {
  const struct {
    const char* url;
    const char* says;
  } cases[] = {
      {"bogus://x", "unknown LCM provider 'bogus'"},
      {"239.255.76.67:7667", "expected PROVIDER://NETWORK"},
      {"udpm://239.255.76.67:7667?tll=0", "unknown option 'tll'"},
      {"udpm://239.255.76.67:7667?ttl=300", "ttl must be an integer 0..255"},
      {"udpm://239.255.76.67:7667?ttl", "option 'ttl' has no '='"},
      {"udpm://192.168.1.10:7667", "is not a multicast address"},
      {"udpm://239.255.76.67:0", "port must be 1..65535"},
      {"udpm://localhost:7667", "is not an IPv4 address"},
      {"file://", "needs a path"},
      {"file://x.lcm?mode=q", "mode must be r, w or a"},
  };
  for (const auto& c : cases) {
    EXPECT_NE(lcm_url_error(c.url).find(c.says), std::string::npos)
        << c.url << ": " << lcm_url_error(c.url);
  }
}

}  // namespace
}  // namespace vmass::service
