#include "render/atomic_file.h"

#include <atomic>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>

#include <fcntl.h>
#include <unistd.h>

#include "render/image_io.h"

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
  throw ImageError(path + ": cannot write: " + why);
}

std::string error_text(const char* fallback) { return errno ? std::strerror(errno) : fallback; }

// fsync(2) of a file a writer wrote by name; errno set on failure.
bool sync_file(const std::string& name) {
  const int fd = ::open(name.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  const bool ok = ::fsync(fd) == 0;
  const int saved = errno;
  if (::close(fd) != 0) return false;
  errno = saved;
  return ok;
}

// The whole of `bytes` into a new file `name`: every write(2), the fsync(2)
// and the close(2) checked (a full disk may show at any of them).
bool write_all(const std::string& name, std::string_view bytes) {
  const int fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) return false;
  const char* p = bytes.data();
  std::size_t left = bytes.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      if (n == 0) errno = EIO;
      break;
    }
    p += n;
    left -= std::size_t(n);
  }
  bool ok = left == 0 && ::fsync(fd) == 0;
  const int saved = errno;
  if (::close(fd) != 0) return false;
  errno = saved;
  return ok;
}

// ".NAME.tmp-PID" beside the target, so the rename stays on one file system.
// It must itself be a legal name: for a NAME near NAME_MAX (255 bytes) only
// its start is kept, with a hash of the whole so two long names that share
// a start still differ.
std::string temp_name(const std::string& name) {
  constexpr std::size_t kNameMaxBytes = NAME_MAX;
  const std::string suffix = ".tmp-" + std::to_string(::getpid());
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

void commit(const std::string& path, const std::function<bool(const std::string&)>& writer,
            bool synced) {
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) fail(path, "folder " + dir.string() + " does not exist");
  if (const std::string why = not_replaceable(path); !why.empty()) fail(path, why);
  const std::string tmp = (dir / temp_name(target.filename().string())).string();
  const ListedTemp listed(tmp);
  errno = 0;  // so a failure's reason is the writer's, not an older one
  std::string why;
  if (!writer(tmp)) why = error_text("write failed");
  else if (!synced && !sync_file(tmp)) why = error_text("fsync failed");
  // The target may have become something else while the file was written.
  if (why.empty()) why = not_replaceable(path);
  if (why.empty() && ::rename(tmp.c_str(), path.c_str()) != 0) why = error_text("rename failed");
  if (!why.empty()) {
    ::unlink(tmp.c_str());
    fail(path, why);
  }
}

}  // namespace

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
  commit(path, writer, false);
}

void write_bytes_atomically(const std::string& path, std::string_view bytes) {
  commit(path, [&](const std::string& tmp) { return write_all(tmp, bytes); }, true);
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
