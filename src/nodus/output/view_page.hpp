#pragma once
/// `nodus view`'s page (docs/view.md): one self-contained HTML file that shows a run and its branches in 3D
/// in a web browser, with no server and no network. The run's states go into the page as JSON with their
/// nodes quantised to 16 bits and base64-encoded; the page's script (web/, bundled with three.js when nodus
/// is built, viewer_bundle.hpp) is inlined after them.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "nodus/output/result_data.hpp"

namespace nodus::output {

/// nodus was built without the page's script (no web/node_modules at configure time): the message says how
/// to get it. `nodus view` exits with status 2 for it.
class ViewerUnavailable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ViewOptions {
  std::string title;  ///< shown on the page; default: the run's name
  /// Budget of the states' data in the page [bytes]. Where all states of the run and its branches would take
  /// more, each run keeps the same fraction of its states, evenly spread, with its first and last state and
  /// the last state of each stage among them (docs/view.md).
  std::uintmax_t max_bytes = 80000000;
  /// VTK node measures (docs/output.md: e11 ... m12) offered in the page as they are, beside the derived
  /// ones that are always there where their inputs are (axial strain e33, axial stress E e33, curvature).
  std::vector<std::string> raw_fields;
};

/// How a value of a state's node record is stored: as the 16-bit integer q, value = lo + q * step, so it is
/// within step / 2 of the value written (lo and step over all the run's kept states, per channel).
struct Quantisation {
  double lo = 0.0;
  double step = 0.0;
};

/// The states of a run kept within `keep` of its `count` states: the first, the last, the last state of each
/// stage (`stage_ends`, indices), then evenly spread ones, in increasing order; all where keep >= count.
std::vector<std::size_t> kept_states(std::size_t count, std::size_t keep,
                                     const std::vector<std::size_t>& stage_ends);

/// The page's data as JSON text (docs/view.md, "What the page holds").
std::string view_page_json(const ResultRun& run, const ViewOptions& options = {});

/// The whole page: the JSON of view_page_json and the page's script. Throws ViewerUnavailable when nodus was
/// built without the script, std::invalid_argument for a run whose arrays disagree in size.
std::string view_page_html(const ResultRun& run, const ViewOptions& options = {});

/// Writes view_page_html to `html` atomically (atomic_file.hpp); throws WriteError where it cannot.
void write_view_page(const ResultRun& run, const std::filesystem::path& html, ViewOptions options = {});

}  // namespace nodus::output
