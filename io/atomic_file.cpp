// io/atomic_file.cpp — unique temporary, checked writes, rename; the signal handler that
// removes temporaries when the process is interrupted.
#include "io/atomic_file.h"

#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <mutex>

#include "io/error.h"

namespace softmol::io {
namespace {

// ---- Temporaries the signal handler removes --------------------------------------------------
// Fixed slots of plain bytes: the handler may only read memory and call unlink (both
// async-signal-safe). state: 0 free, 1 being filled or emptied, 2 holds a live temporary.
// More concurrent temporaries than slots are not registered (they are still removed on every
// path except a signal).
constexpr int kSlots = 16;
struct Slot {
  std::atomic<int> state{0};
  char path[PATH_MAX];
};
Slot g_slots[kSlots];
constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};
struct sigaction g_previous[3];

void RemoveTemporariesAndReraise(int sig) {
  const int saved = errno;
  for (Slot& s : g_slots)
    if (s.state.load(std::memory_order_acquire) == 2) unlink(s.path);
  // Restore what the process had (normally the default action) and re-raise, so the exit status
  // still says "killed by SIGTERM"; the signal is delivered when this handler returns.
  for (int i = 0; i < 3; ++i)
    if (kSignals[i] == sig) sigaction(sig, &g_previous[i], nullptr);
  raise(sig);
  errno = saved;
}

void InstallHandlerOnce() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (int i = 0; i < 3; ++i) {
      struct sigaction sa {};
      sa.sa_handler = RemoveTemporariesAndReraise;
      sigemptyset(&sa.sa_mask);
      sa.sa_flags = 0;
      sigaction(kSignals[i], nullptr, &g_previous[i]);
      if (g_previous[i].sa_handler == SIG_IGN) continue;  // nohup & co: keep ignoring
      sigaction(kSignals[i], &sa, nullptr);
    }
  });
}

// Claims a slot holding `templ`, for mkostemp to fill in place: the name is registered before
// the file exists, so a signal at any moment after its creation finds it. -1 when none is free.
int Register(const std::string& templ) {
  if (templ.size() >= PATH_MAX) return -1;
  InstallHandlerOnce();
  for (int i = 0; i < kSlots; ++i) {
    int expected = 0;
    if (!g_slots[i].state.compare_exchange_strong(expected, 1, std::memory_order_acq_rel)) continue;
    std::memcpy(g_slots[i].path, templ.c_str(), templ.size() + 1);
    g_slots[i].state.store(2, std::memory_order_release);
    return i;
  }
  return -1;
}

void Unregister(int& slot) {
  if (slot >= 0) g_slots[slot].state.store(0, std::memory_order_release);
  slot = -1;
}

// ---- Paths ------------------------------------------------------------------------------------
std::atomic<detail::WriteFunction> g_write{nullptr};

std::string Errno(int err) { return err == 0 ? "the write made no progress" : std::strerror(err); }

std::string ParentOf(const std::string& p) {
  const size_t slash = p.find_last_of('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : p.substr(0, slash);
}

std::string BaseOf(const std::string& p) {
  const size_t slash = p.find_last_of('/');
  return slash == std::string::npos ? p : p.substr(slash + 1);
}

// Follows a chain of symlinks to the file that will be replaced (cp's behaviour).
std::string ResolveOutput(const std::string& output) {
  std::string p = output;
  for (int hops = 0;; ++hops) {
    struct stat st {};
    if (lstat(p.c_str(), &st) != 0) {
      if (errno == ENOENT) return p;  // a new file, or the missing target of a dangling link
      if (errno == ENOTDIR) throw InputError({output}, "'" + ParentOf(p) + "' is not a folder");
      throw InputError({output}, "cannot write the output: " + Errno(errno));
    }
    if (S_ISDIR(st.st_mode)) throw InputError({output}, "the output is a directory");
    // A device or FIFO must not be replaced by a renamed regular file (think /dev/null as root).
    if (S_ISREG(st.st_mode)) return p;
    if (!S_ISLNK(st.st_mode)) throw InputError({output}, "the output exists and is not a regular file");
    if (hops == 40) throw InputError({output}, "too many levels of symbolic links");
    char link[PATH_MAX];
    const ssize_t n = readlink(p.c_str(), link, sizeof link - 1);
    if (n < 0) throw InputError({output}, "cannot read the symbolic link: " + Errno(errno));
    link[n] = '\0';
    p = (link[0] == '/' || p.find('/') == std::string::npos) ? std::string(link)
                                                             : ParentOf(p) + "/" + link;
  }
}

void CheckFolder(const std::string& output, const std::string& folder) {
  struct stat st {};
  if (stat(folder.c_str(), &st) != 0) {
    if (errno == ENOENT) throw InputError({output}, "the output folder '" + folder + "' does not exist");
    throw InputError({output}, "cannot use the output folder '" + folder + "': " + Errno(errno));
  }
  if (!S_ISDIR(st.st_mode)) throw InputError({output}, "'" + folder + "' is not a folder");
}

// The process's umask, read from /proc (umask(2) can only be read by setting it, which would
// race with other threads creating files).
mode_t CurrentUmask() {
  if (FILE* f = std::fopen("/proc/self/status", "re")) {
    char line[256];
    unsigned mask = 0;
    bool found = false;
    while (!found && std::fgets(line, sizeof line, f)) found = std::sscanf(line, "Umask: %o", &mask) == 1;
    std::fclose(f);
    if (found) return mode_t(mask);
  }
  return 022;
}

// The mode the output gets: the replaced file's, or what open(2) would give a new one.
mode_t OutputMode(const std::string& target) {
  struct stat st {};
  if (stat(target.c_str(), &st) == 0 && S_ISREG(st.st_mode)) return st.st_mode & 07777;
  return 0666 & ~CurrentUmask();
}

}  // namespace

TemporaryFile::TemporaryFile(const std::string& output) : output_(output) {
  if (output.empty()) throw InputError({"-o"}, "the output name is empty");
  target_ = ResolveOutput(output);
  const std::string folder = ParentOf(target_);
  CheckFolder(output, folder);
  // ".name.XXXXXX" beside the target: the same file system, so rename() is atomic; the base
  // is shortened so the name stays under NAME_MAX.
  std::string templ = folder + "/." + BaseOf(target_).substr(0, 200) + ".XXXXXX";
  slot_ = Register(templ);
  char* name = slot_ >= 0 ? g_slots[slot_].path : templ.data();
  fd_ = mkostemp(name, O_CLOEXEC);
  if (fd_ < 0) {
    const int err = errno;
    Unregister(slot_);
    throw InputError({output}, "cannot create a file in the folder '" + folder + "': " + Errno(err));
  }
  temp_ = name;
  if (fchmod(fd_, OutputMode(target_)) != 0) Fail("cannot write the output", errno);
}

TemporaryFile::~TemporaryFile() {
  if (committed_) return;
  if (fd_ >= 0) close(fd_);
  if (!temp_.empty()) unlink(temp_.c_str());
  Unregister(slot_);
}

void TemporaryFile::Fail(const std::string& what, int err) {
  if (fd_ >= 0) close(fd_);
  fd_ = -1;
  unlink(temp_.c_str());
  temp_.clear();
  Unregister(slot_);
  throw InputError({output_}, what + ": " + Errno(err));
}

void TemporaryFile::Write(const void* data, size_t size) {
  const detail::WriteFunction f = g_write.load();
  const auto* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = f ? f(fd_, p, size) : ::write(fd_, p, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) Fail("cannot write the output", n < 0 ? errno : 0);
    p += n;
    size -= size_t(n);
  }
}

void TemporaryFile::CloseForExternalWriter() {
  const int fd = fd_;
  fd_ = -1;
  if (fd >= 0 && close(fd) != 0) Fail("cannot write the output", errno);
}

void TemporaryFile::Commit() {
  CloseForExternalWriter();
  if (temp_.empty()) throw InputError({output_}, "internal error: the output was already discarded");
  if (rename(temp_.c_str(), target_.c_str()) != 0) Fail("cannot write the output", errno);
  committed_ = true;
  Unregister(slot_);
}

namespace detail {
void SetWriteFunctionForTesting(WriteFunction f) { g_write.store(f); }
}  // namespace detail

}  // namespace softmol::io
