#include "nodus/output/output_folder.hpp"

#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "nodus/output/atomic_file.hpp"
#include "nodus/scenario/scenario.hpp"

namespace nodus::output {

namespace fs = std::filesystem;

namespace {

/// The folders of one output set (the main run's, or a branch's) that hold files written by AtomicFile.
constexpr const char* kSubfolders[] = {"vtk", "contact", "stages", "checkpoints"};

/// Removes the temporary files directly in `folder` (none if it is not a folder); adds their count to
/// `removed`.
void remove_temporary_files_in(const fs::path& folder, std::size_t& removed) {
  std::error_code error;
  if (!fs::is_directory(folder, error)) return;
  std::vector<fs::path> stale;
  for (const auto& entry : fs::directory_iterator(folder, error)) {
    std::error_code type_error;
    if (entry.is_regular_file(type_error) && is_temporary_file_name(entry.path().filename().string()))
      stale.push_back(entry.path());
  }
  if (error) throw std::runtime_error("cannot list folder '" + folder.string() + "': " + error.message());
  for (const fs::path& path : stale) {
    fs::remove(path, error);
    if (error)
      throw std::runtime_error("cannot remove temporary file '" + path.string() + "': " + error.message());
    ++removed;
  }
}

void remove_in_output_set(const fs::path& dir, std::size_t& removed) {
  remove_temporary_files_in(dir, removed);
  for (const char* sub : kSubfolders) remove_temporary_files_in(dir / sub, removed);
}

}  // namespace

void check_output_folder(const fs::path& dir) {
  const auto fail = [&](const std::string& got) {
    throw scenario::ScenarioError(fmt::format(
        "{}: --out: expected a folder, or a path where one can be created, got {}", dir.string(), got));
  };
  if (dir.empty()) fail("an empty path");
  std::error_code error;
  const fs::file_status status = fs::status(dir, error);
  if (fs::exists(status)) {
    if (!fs::is_directory(status)) fail("an existing file that is not a folder");
    return;
  }
  // It does not exist: its nearest existing ancestor must be a folder.
  const fs::path absolute = fs::absolute(dir, error);
  if (error) return;  // the current folder is gone: creating it reports the error
  for (fs::path p = absolute.parent_path();; p = p.parent_path()) {
    const fs::file_status s = fs::status(p, error);
    if (fs::exists(s)) {
      if (!fs::is_directory(s)) fail(fmt::format("a path under the file '{}'", p.string()));
      return;
    }
    if (p == p.parent_path()) return;
  }
}

std::size_t remove_stale_temporary_files(const fs::path& dir) {
  std::size_t removed = 0;
  remove_in_output_set(dir, removed);
  std::error_code error;
  const fs::path branches = dir / "branches";
  if (fs::is_directory(branches, error)) {
    std::vector<fs::path> sets;
    for (const auto& entry : fs::directory_iterator(branches, error)) {
      std::error_code type_error;
      if (entry.is_directory(type_error)) sets.push_back(entry.path());
    }
    if (error) throw std::runtime_error("cannot list folder '" + branches.string() + "': " + error.message());
    for (const fs::path& set : sets) remove_in_output_set(set, removed);
  }
  if (removed > 0)
    spdlog::info("removed {} temporary file(s) left by an interrupted run in {}", removed, dir.string());
  return removed;
}

}  // namespace nodus::output
