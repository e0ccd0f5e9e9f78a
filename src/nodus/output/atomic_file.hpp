#pragma once
/// Writing whole files so that a reader (ParaView, a script polling a running job) never sees a half-written
/// one: the content goes to a temporary file next to the target, which is then renamed over it (atomic on
/// POSIX file systems).

#include <filesystem>
#include <fstream>
#include <string_view>

namespace nodus::output {

/// A file being written: stream into `stream()`, then `commit()` renames the temporary file onto the target.
/// Destroyed without commit (an exception on the way), it removes the temporary file and leaves the target as
/// it was. Errors throw std::runtime_error naming the path.
class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ostream& stream() { return out_; }
  const std::filesystem::path& path() const { return path_; }
  /// Flushes, closes and renames onto the target. Throws if any write failed.
  void commit();

 private:
  std::filesystem::path path_;
  std::filesystem::path temp_;
  std::ofstream out_;
  bool committed_ = false;
};

/// Writes `content` as the whole of file `path` through a temporary file and a rename.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

}  // namespace nodus::output
