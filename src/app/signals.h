// Ctrl-C (SIGINT), SIGTERM and SIGHUP: never a temporary file left behind, and in a
// headless render the passes completed are written before the exit
// (docs/RELIABILITY.md, promises 5-7).
#pragma once

namespace whisker {

// Installs the handlers for SIGINT, SIGTERM and SIGHUP (a signal ignored when the
// program started, as in a background job of a shell without job control,
// stays ignored). With `graceful`, the first signal only asks the program
// to stop (interrupt_signal() turns non-zero; the headless render polls it);
// a second one, or the first without `graceful`, removes the temporary
// files being written and ends the process at once with 128 + the signal's
// number (130 for SIGINT, 143 for SIGTERM, 129 for SIGHUP).
void install_signal_handlers(bool graceful);

// SIGPIPE ignored: a reader of the progress or the summary that went away
// (`whisker ... 2>&1 | head -c1`) makes those writes fail, which is harmless,
// instead of killing the render before its outputs are written.
void ignore_broken_pipes();

// The signal that asked the program to stop, or 0.
int interrupt_signal();

// The exit code after an interrupted run: 128 + the signal's number.
inline int interrupted_exit_code(int signal) { return 128 + signal; }

}  // namespace whisker
