#pragma once
/// One run at a time in an output folder: an exclusive lock on the folder itself (flock), held while the run
/// writes into it and released by the kernel when the process ends, however it ends (a killed run never
/// blocks the next one).

#include <filesystem>

namespace nodus::output {

class FolderLock {
 public:
  /// Locks the folder `dir` (it must exist). Throws scenario::ScenarioError (bad input, one line) if another
  /// process holds it, naming that process where /proc/locks tells it; std::runtime_error if the folder
  /// cannot be opened. Where the file system refuses the lock itself (some NFS mounts), it warns and holds
  /// nothing.
  explicit FolderLock(const std::filesystem::path& dir);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace nodus::output
