#pragma once
/// Writing whole files so that a reader (ParaView, a script polling a running job) never sees a half-written
/// one: the content goes to a temporary file next to the target, which is then renamed over it (atomic on
/// POSIX file systems).

#include <cstdint>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>

namespace nodus::output {

/// A file of a run's output that could not be written: the message names the file and the system's reason
/// ("No space left on device", "Permission denied", "Read-only file system"). `nodus run` exits with status 4
/// for it; what was written before stays as it was, so that the run resumes once the cause is removed.
class WriteError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Throws WriteError "cannot WHAT 'PATH': REASON", REASON from errno `error`.
[[noreturn]] void throw_write_error(std::string_view what, const std::filesystem::path& path, int error);

/// Throws WriteError "cannot write 'PATH': No space left on device (it takes N, M are free)" if the file
/// system of `folder` says it has fewer than `bytes` bytes available; does nothing where it cannot tell.
void require_space(const std::filesystem::path& folder, std::uintmax_t bytes,
                   const std::filesystem::path& path);

/// "12.3 MB", "456 kB", "789 bytes": a size for a message (decimal units).
std::string human_size(std::uintmax_t bytes);

/// A file being written: stream into `stream()` (held in memory), then `commit()` writes it to the temporary
/// file and renames that onto the target; it first checks that the file system has room for it
/// (require_space). Destroyed without commit (an exception on the way), it removes the
/// temporary file and leaves the target as it was. Errors throw WriteError naming the path and the reason.
class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ostream& stream() { return buffer_; }
  /// The bytes streamed so far.
  std::uintmax_t size() { return static_cast<std::uintmax_t>(buffer_.tellp()); }
  const std::filesystem::path& path() const { return path_; }
  /// Writes the content, closes and renames onto the target. Throws WriteError if any of it failed.
  void commit();

 private:
  std::filesystem::path path_;
  std::filesystem::path temp_;
  std::ostringstream buffer_;
  int fd_ = -1;  ///< the temporary file, open from the constructor to commit()
  bool committed_ = false;
};

/// The temporary file of AtomicFile for target `path` written by process `pid`: "TARGET.tmpPID" next to it
/// (the pid keeps two processes writing into the same folder from sharing a temporary file).
std::filesystem::path temporary_path(const std::filesystem::path& path, long pid);

/// Whether `file_name` (a name, no folder) is that of a temporary file of AtomicFile for one of nodus's
/// output files: "NAME.EXT.tmpPID" with EXT one of csv, vtp, pvd, json, xmf, nodus-state. A run killed while
/// writing leaves such a file behind (see remove_stale_temporary_files in output_folder.hpp).
bool is_temporary_file_name(std::string_view file_name);

/// Writes `content` as the whole of file `path` through a temporary file and a rename.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

}  // namespace nodus::output
