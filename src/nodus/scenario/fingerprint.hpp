#pragma once
/// The fingerprint of a saved state of a run: the text that identifies what made it, and its hash.

#include <cstdint>
#include <string>
#include <string_view>

namespace nodus::scenario {

struct Scenario;

/// The text that identifies a saved state of a run of `scenario` in which the first `stages_run` stages were
/// begun (the one in progress included): a canonical serialisation, one line "PATH = VALUE" per value, of
/// everything that made that state (materials, beams, conditions, solver, contact, those stages, and for a
/// branch its friction): every declared key (key.hpp) in declaration order, numbers in full precision
/// (%.17g), and the structural parts (names, indices, vectors, dofs). It leaves out what may change between
/// saving and resuming without changing the state: the file path, line numbers, output settings and the
/// stages still to come. It does not depend on the echo (describe()), so rewording the echo keeps
/// checkpoints valid, while any change of a value changes it.
std::string state_fingerprint_text(const Scenario& scenario, int stages_run);

/// 64-bit FNV-1a hash of `text` (the fingerprint of a saved state).
std::uint64_t fingerprint_hash(std::string_view text);

}  // namespace nodus::scenario
