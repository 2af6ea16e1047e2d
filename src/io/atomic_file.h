// Output files written whole or not at all: every writer writes a new
// temporary file beside its target (unnamed, O_TMPFILE, where the file
// system allows; else ".NAME.tmp-RANDOM", created exclusively, never through
// a symbolic link), checks every write and the fsync, and the file is renamed
// into place only then. Named temporary files in progress are listed so
// that a signal handler can remove them.
#pragma once

#include <functional>
#include <string>
#include <string_view>

namespace whisker {

// `path` as a message shows it, one line: whole if it has at most
// kQuoteMax bytes, else its start and its end (the file's name) around
// "...", so that the reason after it is never cut off (a path may be
// PATH_MAX bytes long). Control characters escaped.
std::string path_for_message(std::string_view path);

// Why an output cannot go in the folder `dir` ("" if it can be looked up as
// a folder): "folder DIR does not exist", "X is not a folder" (a file where
// a folder of the path should be), or "folder DIR: REASON" (too long a name,
// a symbolic link loop, a folder that cannot be searched).
std::string folder_problem(const std::string& dir);

// Why an output may not go to `path` ("" if it may): it names something
// that is not a regular file (a directory, FIFO, device node, socket, or a
// symbolic link to one), which the rename would replace.
std::string not_replaceable(const std::string& path);

// Runs writer(name) beside `path`, where opening `name` (O_TRUNC is fine)
// opens the new temporary file itself (a /proc/self/fd link, or its own
// name without /proc); syncs the result to disk and renames it onto `path`;
// on any failure removes the temporary file and throws ImageError
// "PATH: cannot write: REASON".
void write_file_atomically(const std::string& path,
                           const std::function<bool(const std::string&)>& writer);

// `bytes` as the whole content of `path`, the same way, with checked
// write(2), fsync(2) and close(2).
void write_bytes_atomically(const std::string& path, std::string_view bytes);

// Removes the temporary files being written now. Async-signal-safe (only
// unlink(2) on names kept in static storage): for SIGINT/SIGTERM handlers.
void remove_temp_files_now() noexcept;

}  // namespace whisker
