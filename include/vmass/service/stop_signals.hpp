// vmassd's stop signals (SIGTERM, SIGINT), handled from the first instruction of main to the
// exit, so that no start-up step (a slow disk, a FIFO where a file was expected) can leave the
// daemon deaf to `systemctl stop`:
//
//   install_stop_signals()   first thing in main: until block_stop_signals(), SIGTERM or SIGINT
//                            ends the process at once with exit code 0 (nothing is estimated
//                            or saved yet), saying "vmassd: stopped during start-up" (in the
//                            journal's form when stderr is the journal, journal_logging.hpp);
//                            SIGHUP does nothing (no reload), SIGPIPE is ignored (for good)
//   block_stop_signals()     before the daemon's threads start: the signals are blocked (every
//                            thread started later inherits the mask) and the main loop takes
//                            them with sigtimedwait; one that a thread with the signals
//                            unblocked (started by a library meanwhile) takes instead is left
//                            in stop_requested() for the main loop
//
// Thread-safety: install and block from the main thread; stop_requested() from any thread.
#pragma once

#include <signal.h>

namespace vmass::service {

void install_stop_signals();
/// Blocks SIGTERM, SIGINT and SIGHUP in the calling thread; returns them as a set.
sigset_t block_stop_signals();
/// The stop signal a handler took after block_stop_signals() (0: none).
int stop_requested();

}  // namespace vmass::service
