#include "app/signals.h"

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdint>
#include <ctime>
#include <forward_list>
#include <utility>

#include <unistd.h>

#include "io/atomic_file.h"

namespace whisker {

namespace {

std::atomic<int> g_signal{0};
std::atomic<bool> g_graceful{false};
// When the first request's signal arrived (CLOCK_MONOTONIC, ns); 0 while its
// handler has not stored it yet.
std::atomic<std::int64_t> g_first_ns{0};
std::atomic<const char*> g_note{"nothing written"};
std::forward_list<std::string> g_notes;  // every note set, never changed or freed
static_assert(std::atomic<int>::is_always_lock_free && std::atomic<bool>::is_always_lock_free &&
                  std::atomic<std::int64_t>::is_always_lock_free &&
                  std::atomic<const char*>::is_always_lock_free,
              "read and written from a signal handler");

std::int64_t monotonic_ns() {
  timespec ts{};
  ::clock_gettime(CLOCK_MONOTONIC, &ts);  // async-signal-safe (POSIX)
  return std::max<std::int64_t>(1, std::int64_t(ts.tv_sec) * 1000000000 + ts.tv_nsec);
}

const char* signal_name(int sig) {
  switch (sig) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case SIGHUP: return "SIGHUP";
    default: return "a signal";
  }
}

// Appends `s` to buf[0, n) while it fits (the last byte kept for '\n').
void append(char* buf, std::size_t& n, std::size_t cap, const char* s) {
  for (; *s && n + 1 < cap; ++s) buf[n++] = *s;
}

// "whisker: second request to stop (SIGINT after SIGTERM): stopped at once;
// NOTE", in one write(2) (whole if at most PIPE_BUF bytes, as a note of
// usual names is).
void say_stopped(int first, int sig) {
  char buf[4096];
  std::size_t n = 0;
  append(buf, n, sizeof buf, "whisker: second request to stop (");
  append(buf, n, sizeof buf, signal_name(sig));
  append(buf, n, sizeof buf, first == sig ? " again" : " after ");
  if (first != sig) append(buf, n, sizeof buf, signal_name(first));
  append(buf, n, sizeof buf, "): stopped at once; ");
  append(buf, n, sizeof buf, g_note.load());
  buf[n++] = '\n';
  const ssize_t ignored = ::write(2, buf, n);  // nothing to do if stderr is gone
  (void)ignored;
}

// Async-signal-safe only: atomics, clock_gettime(2), unlink(2) (in
// remove_temp_files_now), write(2), _exit(2). Two copies may run at once on
// two threads (a process-directed signal goes to any thread): the exchange
// on g_signal makes one of them the first.
extern "C" void on_signal(int sig) {
  const bool graceful = g_graceful.load();
  int first = 0;
  if (graceful) {
    const std::int64_t now = monotonic_ns();
    if (g_signal.compare_exchange_strong(first, sig)) {  // the first: stop politely
      g_first_ns.store(now);
      return;
    }
    const std::int64_t t0 = g_first_ns.load();  // 0: the first's handler is running now
    if (first == sig && (t0 == 0 || now - t0 < std::int64_t(kSameRequestSeconds * 1e9))) return;
  }
  remove_temp_files_now();
  if (graceful) say_stopped(first, sig);
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
    sigaddset(&sa.sa_mask, SIGINT);  // one handler at a time in a thread
    sigaddset(&sa.sa_mask, SIGTERM);
    sigaddset(&sa.sa_mask, SIGHUP);
    sa.sa_flags = SA_RESTART;  // reads and writes in progress go on
    ::sigaction(sig, &sa, nullptr);
  }
}

void set_stop_note(std::string note) {
  g_notes.push_front(std::move(note));
  g_note.store(g_notes.front().c_str());
}

void ignore_broken_pipes() {
  struct sigaction sa {};
  sa.sa_handler = SIG_IGN;
  sigemptyset(&sa.sa_mask);
  ::sigaction(SIGPIPE, &sa, nullptr);
}

int interrupt_signal() { return g_signal.load(); }

}  // namespace whisker
