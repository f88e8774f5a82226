// Whether an LCM URL can be what it says, before LCM is asked to open it. liblcm refuses an
// unknown provider only when it opens it (vmassd then exits 1, "cannot open", and systemd
// restarts it forever) and ignores an option it does not know with a warning on stderr (a typo
// such as `tll=0` would send every estimate off the host). Both are configuration errors:
// refused here, so that vmassd exits 2 (RestartPreventExitStatus) with the reason.
//
//   PROVIDER://NETWORK[?KEY=VALUE[&KEY=VALUE...]]
//   udpm, mpudpm   NETWORK = IPv4 multicast address (224.0.0.0/4) ':' port 1..65535;
//                  keys ttl (0..255) and recv_buf_size (> 0), integers
//   file           NETWORK = a path; keys mode (r, w, a), speed (> 0), start_timestamp
//   memq, tcpq     as liblcm reads them (NETWORK, and keys, not checked further)
//
// A URL that passes can still fail to open (no route for multicast, a file that cannot be
// created): that is a start-up failure, exit 1, which systemd retries.
#pragma once

#include <string>

namespace vmass::service {

/// "" when the URL is well formed, else why not (without the key's name).
std::string lcm_url_error(const std::string& url);

}  // namespace vmass::service
