#include "nodus/output/folder_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "nodus/scenario/scenario.hpp"

namespace nodus::output {

namespace {

/// The process holding a flock on the file with device `device` and inode `inode`, from /proc/locks
/// ("1: FLOCK  ADVISORY  WRITE PID MAJ:MIN:INODE 0 EOF", MAJ and MIN in hexadecimal).
std::optional<long> flock_holder(dev_t device, ino_t inode) {
  std::ifstream locks("/proc/locks");
  const std::string file = fmt::format("{:02x}:{:02x}:{}", major(device), minor(device), inode);
  for (std::string line; std::getline(locks, line);) {
    std::istringstream words(line);
    std::string number, kind, mode, access, pid, where;
    if (!(words >> number >> kind >> mode >> access >> pid >> where) || kind != "FLOCK") continue;
    if (where == file) return std::stol(pid);
  }
  return std::nullopt;
}

}  // namespace

FolderLock::FolderLock(const std::filesystem::path& dir) {
  // O_CLOEXEC: the processes a run starts (its branches) must not inherit the lock.
  fd_ = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd_ < 0)
    throw std::runtime_error(fmt::format("cannot open folder '{}': {}", dir.string(), std::strerror(errno)));
  if (::flock(fd_, LOCK_EX | LOCK_NB) == 0) return;
  const int error = errno;
  struct stat info = {};
  const std::optional<long> holder = error == EWOULDBLOCK && ::fstat(fd_, &info) == 0
                                         ? flock_holder(info.st_dev, info.st_ino)
                                         : std::nullopt;
  ::close(fd_);
  fd_ = -1;
  if (error != EWOULDBLOCK) {
    // Some network file systems refuse flock (NFS without lock support: ENOLCK; on a read-only descriptor:
    // EBADF): the run goes on, unguarded, rather than not at all.
    spdlog::warn(
        "cannot lock folder '{}' ({}): a second run into it would not be refused on this file system",
        dir.string(), std::strerror(error));
    return;
  }
  throw scenario::ScenarioError(fmt::format(
      "{}: --out: expected a folder no other run is writing into, got one that {} is writing into (let it "
      "end, "
      "stop it, or choose another folder)",
      dir.string(), holder ? fmt::format("process {}", *holder) : std::string("another process")));
}

FolderLock::~FolderLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the lock
}

}  // namespace nodus::output
