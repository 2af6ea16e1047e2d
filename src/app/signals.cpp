#include "app/signals.h"

#include <atomic>
#include <csignal>

#include <unistd.h>

#include "io/atomic_file.h"

namespace whisker {

namespace {

std::atomic<int> g_signal{0};
std::atomic<bool> g_graceful{false};
static_assert(std::atomic<int>::is_always_lock_free && std::atomic<bool>::is_always_lock_free,
              "read and written from a signal handler");

// Async-signal-safe only: atomics, unlink(2) (in remove_temp_files_now),
// _exit(2).
extern "C" void on_signal(int sig) {
  if (g_graceful.load() && g_signal.exchange(sig) == 0) return;  // the first: stop politely
  remove_temp_files_now();
  ::_exit(interrupted_exit_code(sig));
}

}  // namespace

void install_signal_handlers(bool graceful) {
  g_graceful.store(graceful);
  // SIGHUP (the terminal or the ssh session closed) as SIGTERM: it killed a
  // render with nothing written, and left a write's temporary file behind.
  for (const int sig : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction old {};
    if (::sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    struct sigaction sa {};
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sigaddset(&sa.sa_mask, SIGINT);  // one handler at a time
    sigaddset(&sa.sa_mask, SIGTERM);
    sigaddset(&sa.sa_mask, SIGHUP);
    sa.sa_flags = SA_RESTART;  // reads and writes in progress go on
    ::sigaction(sig, &sa, nullptr);
  }
}

void ignore_broken_pipes() {
  struct sigaction sa {};
  sa.sa_handler = SIG_IGN;
  sigemptyset(&sa.sa_mask);
  ::sigaction(SIGPIPE, &sa, nullptr);
}

int interrupt_signal() { return g_signal.load(); }

}  // namespace whisker
