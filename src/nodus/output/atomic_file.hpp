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

/// The temporary file of AtomicFile for target `path` written by process `pid`: "TARGET.tmpPID" next to it
/// (the pid keeps two processes writing into the same folder from sharing a temporary file).
std::filesystem::path temporary_path(const std::filesystem::path& path, long pid);

/// Whether `file_name` (a name, no folder) is that of a temporary file of AtomicFile for one of nodus's
/// output files: "NAME.EXT.tmpPID" with EXT one of csv, vtp, pvd, json, nodus-state. A run killed while
/// writing leaves such a file behind (see remove_stale_temporary_files in output_folder.hpp).
bool is_temporary_file_name(std::string_view file_name);

/// Writes `content` as the whole of file `path` through a temporary file and a rename.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

}  // namespace nodus::output
