// Ctrl-C (SIGINT), SIGTERM and SIGHUP: never a temporary file left behind, and in a
// headless render the passes completed are written before the exit
// (docs/RELIABILITY.md, promises 5-7).
#pragma once

#include <string>

namespace whisker {

// Installs the handlers for SIGINT, SIGTERM and SIGHUP (a signal ignored when the
// program started, as in a background job of a shell without job control,
// stays ignored). With `graceful`, the first request only asks the program
// to stop (interrupt_signal() turns non-zero; the headless render polls it);
// a second request, or the first without `graceful`, removes the temporary
// files being written and ends the process at once with 128 + the signal's
// number (130 for SIGINT, 143 for SIGTERM, 129 for SIGHUP); with `graceful`
// it first says so on stderr, with the stop note (set_stop_note).
//
// One request, many copies: `timeout`, Slurm, systemd and a shell's `kill`
// of a job send the signal to the process and then to its process group, so
// a program in that group gets it twice within microseconds. Copies of the
// first signal within kSameRequestSeconds of it are that one request; a
// different signal, or the same one later, is a second request.
void install_signal_handlers(bool graceful);
constexpr double kSameRequestSeconds = 1.0;

// What a second request's message says was and was not written, after
// "whisker: second request to stop (SIGINT after SIGTERM): stopped at once; "
// (e.g. "wrote a.png; not written: b.pfm, s.json"); "nothing written" until
// set. The main thread's
// to call (not async-signal-safe); each note is kept to the end, so that a
// handler may read the latest at any time.
void set_stop_note(std::string note);

// SIGPIPE ignored: a reader of the progress or the summary that went away
// (`whisker ... 2>&1 | head -c1`) makes those writes fail, which is harmless,
// instead of killing the render before its outputs are written.
void ignore_broken_pipes();

// The signal that asked the program to stop, or 0.
int interrupt_signal();

// The exit code after an interrupted run: 128 + the signal's number.
inline int interrupted_exit_code(int signal) { return 128 + signal; }

}  // namespace whisker
