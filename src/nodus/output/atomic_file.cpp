#include "nodus/output/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <regex>
#include <string>
#include <system_error>

#include <fmt/format.h>

namespace nodus::output {

std::filesystem::path temporary_path(const std::filesystem::path& path, long pid) {
  std::filesystem::path temp = path;
  temp += ".tmp" + std::to_string(pid);
  return temp;
}

bool is_temporary_file_name(std::string_view file_name) {
  static const std::regex pattern(R"(.+\.(csv|vtp|pvd|json|xmf|nodus-state)\.tmp[0-9]+)");
  return std::regex_match(file_name.begin(), file_name.end(), pattern);
}

void throw_write_error(std::string_view what, const std::filesystem::path& path, int error) {
  throw WriteError("cannot " + std::string(what) + " '" + path.string() + "': " + std::strerror(error));
}

void require_space(const std::filesystem::path& folder, std::uintmax_t bytes,
                   const std::filesystem::path& path) {
  std::error_code error;
  const std::filesystem::space_info space = std::filesystem::space(folder, error);
  if (error || space.available == static_cast<std::uintmax_t>(-1) || space.available >= bytes) return;
  throw WriteError(fmt::format("cannot write '{}': {} (it takes {}, {} are free)", path.string(),
                               std::strerror(ENOSPC), human_size(bytes), human_size(space.available)));
}

std::string human_size(std::uintmax_t bytes) {
  const auto b = static_cast<double>(bytes);
  if (b >= 1e9) return fmt::format("{:.1f} GB", b / 1e9);
  if (b >= 1e6) return fmt::format("{:.1f} MB", b / 1e6);
  if (b >= 1e3) return fmt::format("{:.0f} kB", b / 1e3);
  return fmt::format("{} bytes", bytes);
}

AtomicFile::AtomicFile(std::filesystem::path path)
    : path_(std::move(path)), temp_(temporary_path(path_, static_cast<long>(::getpid()))) {
  fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) throw_write_error("create", temp_, errno);
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  if (fd_ >= 0) ::close(fd_);
  std::error_code ignored;
  std::filesystem::remove(temp_, ignored);
}

void AtomicFile::commit() {
  const std::string content = std::move(buffer_).str();
  require_space(temp_.has_parent_path() ? temp_.parent_path() : ".", content.size(), path_);
  for (std::size_t done = 0; done < content.size();) {
    const ssize_t n = ::write(fd_, content.data() + done, content.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw_write_error("write", path_, errno);
    done += static_cast<std::size_t>(n);
  }
  // Some file systems (NFS) report a full disk only when the file is closed.
  const int closed = ::close(fd_);
  fd_ = -1;
  if (closed != 0) throw_write_error("write", path_, errno);
  std::error_code error;
  std::filesystem::rename(temp_, path_, error);
  if (error) throw_write_error("rename '" + temp_.string() + "' onto", path_, error.value());
  committed_ = true;
}

void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  AtomicFile file(path);
  file.stream().write(content.data(), static_cast<std::streamsize>(content.size()));
  file.commit();
}

}  // namespace nodus::output
