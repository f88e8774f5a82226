#include "vmass/service/stop_signals.hpp"

#include <unistd.h>

#include <atomic>

#include "vmass/service/journal_logging.hpp"

namespace vmass::service {
namespace {

std::atomic<bool> g_serving{false};
std::atomic<int> g_stop_signal{0};
std::atomic<bool> g_journal{false};  ///< stderr is the journal: its form (journal_logging.hpp)
static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free,
              "touched from a signal handler");

// Async-signal-safe: atomics, write(2) and _exit(2) only.
void on_stop_signal(int sig) {
  if (sig == SIGHUP) return;  // a reload: not supported, logged by the main loop when serving
  if (!g_serving.load()) {
    constexpr char kMessage[] = "vmassd: stopped during start-up\n";
    constexpr char kJournalMessage[] = "<6>stopped during start-up\n";
    const ssize_t ignored =
        g_journal.load() ? ::write(STDERR_FILENO, kJournalMessage, sizeof kJournalMessage - 1)
                         : ::write(STDERR_FILENO, kMessage, sizeof kMessage - 1);
    (void)ignored;
    ::_exit(0);
  }
  g_stop_signal.store(sig);
}

}  // namespace

void install_stop_signals() {
  g_journal.store(stderr_is_journal());
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;  // no SA_RESTART: a blocking call is interrupted, not resumed
  sigaction(SIGTERM, &action, nullptr);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGHUP, &action, nullptr);  // a handler, not SIG_IGN: blocked, it stays pending
  struct sigaction ignore {};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  sigaction(SIGPIPE, &ignore, nullptr);
}

sigset_t block_stop_signals() {
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGHUP);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  ::signal(SIGPIPE, SIG_IGN);  // also for callers of run_daemon that did not install
  g_serving.store(true);       // after blocking: a signal from now on is pending, not fatal
  return signals;
}

int stop_requested() { return g_stop_signal.load(); }

}  // namespace vmass::service
