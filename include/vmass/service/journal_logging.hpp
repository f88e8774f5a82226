// Logging of vmassd, fit for where it runs. On a terminal (or a file): "vmassd LEVEL: message",
// coloured when stderr is a terminal. Under systemd, when stderr is connected to the journal
// ($JOURNAL_STREAM names stderr's device:inode, systemd.exec(5)), each line is what sd-daemon(3)
// asks for: its priority prefix (<3> error, <4> warning, <6> info, <7> debug; <2> critical), no
// program name and no time (journald adds both), and one line per message (a newline in a
// message becomes "; ", so a message is never split into entries).
//
// Thread-safety: setup_logging() once at start, before other threads log.
#pragma once

#include <string>
#include <string_view>

namespace vmass::service {

/// True when $JOURNAL_STREAM is set and names the file stderr is open on.
bool stderr_is_journal();

/// One journal line for a message of syslog priority 0..7 (3 error, 4 warning, 6 info, 7 debug):
/// "<P>message\n" with newlines replaced (see above).
std::string journal_line(int priority, std::string_view message);

/// Sets spdlog's default logger for `program`, in the journal's form when stderr_is_journal().
void setup_logging(const std::string& program);

}  // namespace vmass::service
