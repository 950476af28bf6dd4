// ClaimOutputDirectory: one advisory flock per output folder, held for the life of the process.
#include "models/core/output_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <string>

#include "models/core/error.h"
#include "models/core/files.h"

namespace waam {
namespace {

namespace fs = std::filesystem;

// The folders this process holds, by canonical path: the lock fd and the lock file's inode. On normal exit the
// destructor removes each lock file that is still ours, then the kernel drops the locks with the fds.
class HeldLocks {
 public:
  ~HeldLocks() {
    for (const auto& [dir, held] : held_) {
      struct stat now {};
      if (::stat(held.path.c_str(), &now) == 0 && now.st_ino == held.inode) ::unlink(held.path.c_str());
      ::close(held.fd);
    }
  }
  std::mutex mutex;
  struct Held {
    int fd;
    ino_t inode;
    std::string path;
  };
  std::map<std::string, Held> held_;
};

HeldLocks& Locks() {
  static HeldLocks locks;
  return locks;
}

// This process's command line, arguments separated by spaces (from /proc/self/cmdline).
std::string CommandLine() {
  std::ifstream stream("/proc/self/cmdline", std::ios::binary);
  std::string raw((std::istreambuf_iterator<char>(stream)), std::istreambuf_iterator<char>());
  for (char& c : raw) {
    if (c == '\0') c = ' ';
  }
  while (!raw.empty() && raw.back() == ' ') raw.pop_back();
  return raw;
}

// The first line of a held lock file ("pid <n>"), for the refusal message; "an unknown process" if unreadable.
std::string Holder(int fd) {
  char buffer[512] = {};
  const ssize_t n = ::pread(fd, buffer, sizeof(buffer) - 1, 0);
  std::string text = n > 0 ? std::string(buffer, static_cast<std::size_t>(n)) : std::string();
  std::istringstream lines(text);
  std::string pid_line, command_line;
  std::getline(lines, pid_line);
  std::getline(lines, command_line);
  if (pid_line.rfind("pid ", 0) != 0) return "an unknown process";
  std::string holder = "pid " + pid_line.substr(4);
  if (!command_line.empty()) holder += " (" + command_line + ")";
  return holder;
}

}  // namespace

void ClaimOutputDirectory(const fs::path& dir) {
  EnsureOutputDirectory(dir);
  std::error_code ec;
  const std::string key = fs::weakly_canonical(dir, ec).string();
  HeldLocks& locks = Locks();
  std::lock_guard<std::mutex> guard(locks.mutex);
  if (locks.held_.count(key) != 0) return;
  const std::string path = (dir / kOutputLockName).string();
  // Retry if the file we locked was unlinked by its previous holder between our open and our flock.
  for (int attempt = 0; attempt < 8; ++attempt) {
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    WAAM_THROW_UNLESS(fd >= 0, "output folder " << dir.string() << ": cannot create its lock file " << kOutputLockName
                                                << ": " << std::strerror(errno));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      const std::string holder = Holder(fd);
      ::close(fd);
      WAAM_THROW_UNLESS(error != EWOULDBLOCK, "output folder " << dir.string() << " is in use by " << holder
                                                  << ": wait for it to finish or give another --out");
      WAAM_THROW("output folder " << dir.string() << ": cannot lock " << kOutputLockName << ": "
                                  << std::strerror(error));
    }
    struct stat opened {}, named {};
    if (::fstat(fd, &opened) != 0 || ::stat(path.c_str(), &named) != 0 || opened.st_ino != named.st_ino) {
      ::close(fd);
      continue;
    }
    const std::string contents = "pid " + std::to_string(::getpid()) + "\n" + CommandLine() + "\n";
    // If the description cannot be written the lock still holds; a refusal then names "an unknown process".
    const bool described = ::ftruncate(fd, 0) == 0 && ::pwrite(fd, contents.data(), contents.size(), 0) >= 0;
    static_cast<void>(described);
    locks.held_[key] = HeldLocks::Held{fd, opened.st_ino, path};
    return;
  }
  WAAM_THROW("output folder " << dir.string() << ": its lock file " << kOutputLockName
                              << " keeps being replaced by another process");
}

}  // namespace waam
