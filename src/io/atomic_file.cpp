#include "io/atomic_file.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>

#include <fcntl.h>
#include <sys/random.h>
#include <unistd.h>

#include "io/image_error.h"
#include "scene/quote.h"

namespace whisker {

namespace fs = std::filesystem;

namespace {

// The temporary files being written, for remove_temp_files_now(): fixed
// slots in static storage, since a signal handler may neither allocate nor
// lock. A slot is free (0), being filled (1), listed (2) or being read by a
// handler (3).
constexpr int kSlots = 16;
constexpr std::size_t kNameMax = 4096;  // PATH_MAX: longer names cannot be created anyway
struct Slot {
  std::atomic<int> state{0};
  char name[kNameMax];
};
Slot g_slots[kSlots];
static_assert(std::atomic<int>::is_always_lock_free, "used from a signal handler");

// Lists a temporary file's name for as long as it lives.
class ListedTemp {
 public:
  explicit ListedTemp(const std::string& name) {
    if (name.size() >= kNameMax) return;
    for (int i = 0; i < kSlots && slot_ < 0; ++i) {
      int expected = 0;
      if (!g_slots[i].state.compare_exchange_strong(expected, 1)) continue;
      std::memcpy(g_slots[i].name, name.c_str(), name.size() + 1);
      g_slots[i].state.store(2);
      slot_ = i;
    }
  }
  ~ListedTemp() {
    if (slot_ < 0) return;
    // A handler on another thread may be reading the name: wait for it.
    for (int expected = 2; !g_slots[slot_].state.compare_exchange_weak(expected, 0); expected = 2) {
    }
  }
  ListedTemp(const ListedTemp&) = delete;
  ListedTemp& operator=(const ListedTemp&) = delete;

 private:
  int slot_ = -1;
};

[[noreturn]] void fail(const std::string& path, const std::string& why) {
  throw ImageError(path_for_message(path) + ": cannot write: " + why);
}

// The first `n` bytes of `s`, or fewer so as not to split a UTF-8 character
// (at_end: the last ones).
std::string_view utf8_part(std::string_view s, std::size_t n, bool at_end) {
  const auto continuation = [&s](std::size_t i) {
    return i < s.size() && (static_cast<unsigned char>(s[i]) & 0xC0) == 0x80;
  };
  if (!at_end) {
    while (n > 0 && continuation(n)) --n;
    return s.substr(0, n);
  }
  std::size_t from = s.size() - n;
  while (from < s.size() && continuation(from)) ++from;
  return s.substr(from);
}

std::string error_text(const char* fallback) { return errno ? std::strerror(errno) : fallback; }

// Random letters for a temporary file's name, from getrandom(2); if that
// fails (a kernel before 3.17, a seccomp filter), from the clock, the pid and
// a counter: names that still differ, and O_EXCL makes a clash an EEXIST.
std::string random_letters(std::size_t n) {
  static const char kAlphabet[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  unsigned char bytes[32] = {};
  n = std::min(n, sizeof bytes);
  if (::getrandom(bytes, n, GRND_NONBLOCK) != ssize_t(n)) {
    static std::atomic<std::uint64_t> counter{0};
    std::uint64_t x = std::uint64_t(std::chrono::steady_clock::now().time_since_epoch().count()) ^
                      (std::uint64_t(::getpid()) << 32) ^ (counter.fetch_add(1) * 0x9e3779b97f4a7c15ull);
    for (std::size_t i = 0; i < n; ++i) {
      x ^= x >> 29;
      x *= 0xbf58476d1ce4e5b9ull;
      bytes[i] = static_cast<unsigned char>(x >> 56);
    }
  }
  std::string out;
  for (std::size_t i = 0; i < n; ++i) out += kAlphabet[bytes[i] % (sizeof kAlphabet - 1)];
  return out;
}

// ".NAME.tmp-RANDOM" beside the target, so the rename stays on one file
// system. It must itself be a legal name: for a NAME near NAME_MAX (255
// bytes) only its start is kept, with a hash of the whole so two long names
// that share a start still differ.
std::string temp_name(const std::string& name) {
  constexpr std::size_t kNameMaxBytes = NAME_MAX;
  const std::string suffix = ".tmp-" + random_letters(12);
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "." + s.
  std::string out(1, '.');
  if (1 + name.size() + suffix.size() <= kNameMaxBytes) {
    out.append(name).append(suffix);
    return out;
  }
  char hash[24];
  std::snprintf(hash, sizeof hash, "~%016zx", std::hash<std::string>{}(name));
  const std::size_t keep = kNameMaxBytes - 1 - suffix.size() - std::strlen(hash);
  out.append(name, 0, keep).append(hash).append(suffix);
  return out;
}

// The file being written. Where the file system allows, an unnamed file
// (open(2) O_TMPFILE in the target's folder): nothing to see or to leave
// behind until it is complete. Else a new name made with O_CREAT | O_EXCL
// (never an existing file) and O_NOFOLLOW (never through a symbolic link
// planted there), listed for the signal handlers.
class TempFile {
 public:
  explicit TempFile(const fs::path& dir, const std::string& target_name)
      : dir_(dir), target_name_(target_name) {
    // O_TMPFILE needs O_WRONLY or O_RDWR; EOPNOTSUPP / EISDIR / EINVAL where
    // the file system or the kernel lacks it (open(2), "O_TMPFILE").
    fd_ = ::open(dir.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
    if (fd_ >= 0 && ::access(proc_name().c_str(), F_OK) != 0) {  // no /proc to link it by
      ::close(fd_);
      fd_ = -1;
    }
    if (fd_ >= 0) return;
    for (int attempt = 0; attempt < 100; ++attempt) {
      name_ = (dir / temp_name(target_name)).string();
      listed_ = std::make_unique<ListedTemp>(name_);
      fd_ = ::open(name_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
      if (fd_ >= 0 || errno != EEXIST) break;
    }
    if (fd_ < 0) name_.clear();
  }
  ~TempFile() {
    if (!name_.empty()) ::unlink(name_.c_str());
    if (fd_ >= 0) ::close(fd_);
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;

  int fd() const { return fd_; }
  // A name that opens this very file whatever happens in the folder: its
  // /proc/self/fd link (proc(5): opening it opens the file itself, even an
  // unnamed one), else (no /proc) its own name.
  std::string writer_name() const {
    const std::string p = proc_name();
    return ::access(p.c_str(), F_OK) == 0 || name_.empty() ? p : name_;
  }
  // Renames the complete file onto `target`: an unnamed file is first
  // linked to a new unique name (linkat(2) AT_SYMLINK_FOLLOW on its
  // /proc/self/fd link; a link cannot replace a file, rename(2) can, in one
  // step). errno set on failure.
  bool publish(const std::string& target) {
    if (name_.empty()) {
      for (int attempt = 0; attempt < 100 && name_.empty(); ++attempt) {
        const std::string name = (dir_ / temp_name(target_name_)).string();
        listed_ = std::make_unique<ListedTemp>(name);
        if (::linkat(AT_FDCWD, proc_name().c_str(), AT_FDCWD, name.c_str(), AT_SYMLINK_FOLLOW) == 0)
          name_ = name;
        else if (errno != EEXIST)
          return false;
      }
      if (name_.empty()) return false;
    }
    if (::rename(name_.c_str(), target.c_str()) != 0) return false;
    name_.clear();  // it is the target now
    return true;
  }

 private:
  std::string proc_name() const { return "/proc/self/fd/" + std::to_string(fd_); }

  fs::path dir_;
  std::string target_name_;
  std::string name_;  // "" while unnamed
  int fd_ = -1;
  std::unique_ptr<ListedTemp> listed_;
};

// The whole of `bytes` to `fd`: every write(2) checked (a full disk may
// show at any of them); errno set on failure.
bool write_all(int fd, std::string_view bytes) {
  const char* p = bytes.data();
  std::size_t left = bytes.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      if (n == 0) errno = EIO;
      return false;
    }
    p += n;
    left -= std::size_t(n);
  }
  return true;
}

// Runs `writer` on a fresh temporary file beside `path`: to its descriptor
// (by_fd) or to a name that opens it. Then fsync(2) and the rename; the
// temporary file never outlives the call.
void commit(const std::string& path, const std::function<bool(const std::string&)>& by_name,
            const std::function<bool(int)>& by_fd) {
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (const std::string why = folder_problem(dir.string()); !why.empty()) fail(path, why);
  if (const std::string why = not_replaceable(path); !why.empty()) fail(path, why);
  TempFile tmp(dir, target.filename().string());
  if (tmp.fd() < 0) fail(path, error_text("cannot create a temporary file"));
  errno = 0;  // so a failure's reason is the writer's, not an older one
  std::string why;
  const bool written = by_fd ? by_fd(tmp.fd()) : by_name(tmp.writer_name());
  if (!written) why = error_text("write failed");
  // fsync on any descriptor of the file flushes the file (fsync(2)): the
  // writer's own, closed by now, wrote to the same file.
  else if (::fsync(tmp.fd()) != 0) why = error_text("fsync failed");
  // The target may have become something else while the file was written.
  if (why.empty()) why = not_replaceable(path);
  if (why.empty() && !tmp.publish(path)) why = error_text("rename failed");
  if (!why.empty()) fail(path, why);
}

}  // namespace

std::string path_for_message(std::string_view path) {
  if (path.size() <= kQuoteMax) return printable(path);
  const std::size_t half = kQuoteMax / 2;
  return printable(utf8_part(path, half, false)) + "..." + printable(utf8_part(path, half, true));
}

std::string folder_problem(const std::string& dir) {
  std::error_code ec;
  const fs::file_status st = fs::status(dir, ec);
  if (fs::is_directory(st)) return {};
  if (st.type() != fs::file_type::not_found)
    return fs::exists(st) ? path_for_message(dir) + " is not a folder"
                          : "folder " + path_for_message(dir) + ": " + ec.message();
  // Not there: a file in the way higher up ("afile/sub/x.png") says why.
  for (fs::path up = fs::path(dir).parent_path(); !up.empty(); up = up.parent_path()) {
    const fs::file_status s = fs::status(up, ec);
    if (fs::exists(s)) {
      if (!fs::is_directory(s)) return path_for_message(up.string()) + " is not a folder";
      break;
    }
    if (up == up.parent_path()) break;
  }
  return "folder " + path_for_message(dir) + " does not exist";
}

std::string not_replaceable(const std::string& path) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);  // follows symbolic links
  switch (st.type()) {
    case fs::file_type::not_found:
    case fs::file_type::regular:
      return {};
    case fs::file_type::directory:
      return "is a directory";
    case fs::file_type::fifo:
      return "is a FIFO, not a regular file; refusing to replace it";
    case fs::file_type::character:
    case fs::file_type::block:
      return "is a device, not a regular file; refusing to replace it";
    case fs::file_type::socket:
      return "is a socket, not a regular file; refusing to replace it";
    default:
      break;
  }
  if (ec) return "cannot check what it is: " + ec.message();
  return "is not a regular file; refusing to replace it";
}

void write_file_atomically(const std::string& path,
                           const std::function<bool(const std::string&)>& writer) {
  commit(path, writer, nullptr);
}

void write_bytes_atomically(const std::string& path, std::string_view bytes) {
  commit(path, nullptr, [&](int fd) { return write_all(fd, bytes); });
}

void remove_temp_files_now() noexcept {
  for (Slot& s : g_slots) {
    int expected = 2;
    if (!s.state.compare_exchange_strong(expected, 3)) continue;
    ::unlink(s.name);
    s.state.store(2);
  }
}

}  // namespace whisker
