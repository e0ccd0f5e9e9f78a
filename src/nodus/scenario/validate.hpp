#pragma once
/// Validation of a Scenario built in code (or changed after reading): every check the reader makes on values,
/// against the same key declarations (key.hpp), with the reader's messages minus the line.

namespace nodus::scenario {

struct Scenario;

/// Checks `scenario` as the reader checks a file: each declared scalar key in its range, names unique and
/// non-empty, indices that refer to existing items (where the file names items, a Scenario holds indices),
/// and the checks across keys (ordered contact lengths, the varying friction tangent with umfpack, keyframes,
/// moment axes, ...). Throws ScenarioError "FILE: KEY: expected WHAT, got VALUE" at the first failure, FILE
/// being scenario.path and KEY a concrete path such as beams[2].radius. A scenario that read_scenario
/// returned passes (the reader calls it last). Directions must be unit and director1 orthogonal to them (the
/// reader normalises them).
void validate(const Scenario& scenario);

}  // namespace nodus::scenario
