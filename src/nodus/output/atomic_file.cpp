#include "nodus/output/atomic_file.hpp"

#include <regex>
#include <stdexcept>
#include <system_error>

#include <unistd.h>

namespace nodus::output {

std::filesystem::path temporary_path(const std::filesystem::path& path, long pid) {
  std::filesystem::path temp = path;
  temp += ".tmp" + std::to_string(pid);
  return temp;
}

bool is_temporary_file_name(std::string_view file_name) {
  static const std::regex pattern(R"(.+\.(csv|vtp|pvd|json|nodus-state)\.tmp[0-9]+)");
  return std::regex_match(file_name.begin(), file_name.end(), pattern);
}

AtomicFile::AtomicFile(std::filesystem::path path)
    : path_(std::move(path)), temp_(temporary_path(path_, static_cast<long>(::getpid()))) {
  out_.open(temp_, std::ios::binary | std::ios::trunc);
  if (!out_)
    throw std::runtime_error("cannot open '" + temp_.string() + "' for writing (for '" + path_.string() +
                             "')");
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  out_.close();
  std::error_code ignored;
  std::filesystem::remove(temp_, ignored);
}

void AtomicFile::commit() {
  out_.flush();
  const bool ok = static_cast<bool>(out_);
  out_.close();
  if (!ok || out_.fail()) throw std::runtime_error("error while writing '" + temp_.string() + "'");
  std::error_code error;
  std::filesystem::rename(temp_, path_, error);
  if (error)
    throw std::runtime_error("cannot rename '" + temp_.string() + "' to '" + path_.string() +
                             "': " + error.message());
  committed_ = true;
}

void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  AtomicFile file(path);
  file.stream().write(content.data(), static_cast<std::streamsize>(content.size()));
  file.commit();
}

}  // namespace nodus::output
