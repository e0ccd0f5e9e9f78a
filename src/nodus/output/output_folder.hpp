#pragma once
/// The output folder of a run (`nodus run --out DIR`): checked before anything is read or echoed, and cleared
/// of what a killed run left half-written before a run writes into it. docs/output.md lists its layout.

#include <cstddef>
#include <filesystem>

namespace nodus::output {

/// Checks that `dir` can be a run's output folder: an existing folder, or a path that does not exist and
/// whose nearest existing ancestor is a folder (so that it can be created). Throws scenario::ScenarioError
/// (bad input, exit status 2) with one line "DIR: --out: expected ..., got ..." otherwise: for an existing
/// file, or a path under a file. Permissions are not checked here: writing reports them.
void check_output_folder(const std::filesystem::path& dir);

/// Removes the temporary files (is_temporary_file_name: "NAME.EXT.tmpPID") that a run killed while writing
/// left in the folders nodus writes: DIR and its vtk/, contact/, stages/ and checkpoints/, and the same in
/// each DIR/branches/NAME/. Nothing else is touched, and nothing below those folders. Call it before a run
/// (or a resumed run) writes into DIR, never while another process writes there. Returns how many files
/// were removed (and logs it when there were any); throws std::runtime_error if one cannot be.
std::size_t remove_stale_temporary_files(const std::filesystem::path& dir);

}  // namespace nodus::output
