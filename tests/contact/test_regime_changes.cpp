// The changes of regime of contact elements between evaluations (steps.csv: entered, left, to_slip,
// to_stick): compare_regimes on hand-built states, and ContactTerm's counters over real evaluations of two
// parallel beams whose every contact element presses, opens, sticks or slips together, so that each count is
// the number of elements. Units: mm, N.

#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "contact_test_support.hpp"
#include "nodus/contact/contact_term.hpp"

namespace nodus::contact {
namespace {

using testing::beam_definition;
using testing::constant;
using testing::line;
using testing::place_beam;

ContactState pressing_state(bool slip) {
  ContactState s;
  s.gap = -0.01;
  s.normal_reaction = 2.5;
  s.slip = slip;
  return s;
}

ContactState open_state() {
  ContactState s;
  s.gap = 0.02;
  return s;
}

TEST(RegimeChanges, CountsEachElementAgainstItsOwnPreviousState) {
  // Element by element, from `before` to `now`:
  //   0: open -> pressing (stick)       entered
  //   1: pressing (stick) -> open       left
  //   2: pressing, stick -> slip        to_slip
  //   3: pressing, slip -> stick        to_stick
  //   4: pressing (slip) -> open        left; not to_stick (it no longer presses)
  //   5: open -> pressing (slip)        entered; not to_slip (it did not press before)
  //   6: pressing, slip -> slip         nothing
  //   7: open -> open                   nothing
  const std::vector<ContactState> before{open_state(),         pressing_state(false), pressing_state(false),
                                         pressing_state(true), pressing_state(true),  open_state(),
                                         pressing_state(true), open_state()};
  const std::vector<ContactState> now{pressing_state(false), open_state(), pressing_state(true),
                                      pressing_state(false), open_state(), pressing_state(true),
                                      pressing_state(true),  open_state()};
  const RegimeChanges changes = compare_regimes(before, now);
  EXPECT_EQ(changes.entered, 2);
  EXPECT_EQ(changes.left, 2);
  EXPECT_EQ(changes.to_slip, 1);
  EXPECT_EQ(changes.to_stick, 1);
  // Back again: every change reversed.
  const RegimeChanges back = compare_regimes(now, before);
  EXPECT_EQ(back, (RegimeChanges{2, 2, 1, 1}));
  EXPECT_EQ(compare_regimes(now, now), RegimeChanges{});
  RegimeChanges sum = changes;
  sum += back;
  EXPECT_EQ(sum, (RegimeChanges{4, 4, 2, 2}));
  // States of different element sets cannot be compared.
  EXPECT_THROW(compare_regimes(before, std::vector<ContactState>(before.begin(), before.end() - 1)),
               std::invalid_argument);
}

/// Beam I along x from the origin (R 0.1 mm), beam J along x from x = 1 at distance `distance` in y (R 0.08
/// mm), shifted by `slide` along x: every contact element of the overlap has the gap distance - 0.18 mm and
/// slides by `slide` against its committed state (the state at slide 0).
Eigen::VectorXd side_by_side(const model::Model& model, double distance, double slide) {
  Eigen::VectorXd x = model.reference();
  place_beam(model, x, 0, line(Vec3::Zero(), Vec3::UnitX()), constant(Vec3::UnitZ()));
  place_beam(model, x, 1, line(Vec3(1.0 + slide, distance, 0.0), Vec3::UnitX()), constant(Vec3::UnitZ()));
  return x;
}

struct ParallelBeams {
  model::Model model;
  ContactGeometry geometry;
  Eigen::VectorXd committed;

  ParallelBeams() {
    model.add_beam(beam_definition(4.0, 0.1, 40));
    model.add_beam(beam_definition(4.0, 0.08, 30));
    committed = side_by_side(model, 0.15, 0.0);
    geometry = detect(model, committed, {});
  }
  std::size_t elements() const { return geometry.elements.size(); }
  /// Installs the detected elements in `term` (as after a detection: a new set of elements).
  void install(ContactTerm& term) const {
    term.set_elements(geometry, std::vector<double>(geometry.zones.size(), 100.0),
                      std::vector<Eigen::Vector3d>(geometry.elements.size(), Eigen::Vector3d::Zero()));
  }
  /// Evaluates `term` in the state of beam J at `distance` slid by `slide` (all blocks, or those of
  /// `blocks`).
  void evaluate(ContactTerm& term, double distance, double slide, solver::BlockRange blocks = {}) const {
    const Eigen::VectorXd x = side_by_side(model, distance, slide);
    Eigen::VectorXd residual = Eigen::VectorXd::Zero(model.num_dofs());
    term.add({x, committed, 1.0, 0.0, blocks}, residual, nullptr);
  }
};

/// How many elements press, and how many of them slip, at the last evaluation.
std::pair<int, int> pressing_and_slipping(const ContactTerm& term) {
  int press = 0, slip = 0;
  for (const ContactState& s : term.states()) {
    press += s.normal_reaction > 0.0;
    slip += s.normal_reaction > 0.0 && s.slip;
  }
  return {press, slip};
}

TEST(RegimeChanges, TheContactTermCountsEveryEvaluationOfTheSameElements) {
  const ParallelBeams beams;
  const int n = static_cast<int>(beams.elements());
  ASSERT_GE(n, 50);
  ContactTerm term(beams.model);
  // p_reg 1e-3 mm; friction with g_rev_max 1e-3 mm: a slide of 5e-4 mm sticks, one of 1e-2 mm slips.
  term.set_laws(1e-3, FrictionLaw{0.3, 1e-3});
  beams.install(term);
  const double pressed = 0.15, apart = 0.19;  // gaps -0.03 and +0.01 mm
  const double sticks = 5e-4, slips = 1e-2;

  // The first evaluation of the elements is compared with none.
  beams.evaluate(term, pressed, 0.0);
  ASSERT_EQ(pressing_and_slipping(term), std::make_pair(n, 0));
  EXPECT_EQ(term.regime_changes(), RegimeChanges{});
  beams.evaluate(term, pressed, slips);
  ASSERT_EQ(pressing_and_slipping(term), std::make_pair(n, n));
  EXPECT_EQ(term.regime_changes(), (RegimeChanges{0, 0, n, 0}));
  beams.evaluate(term, pressed, sticks);
  ASSERT_EQ(pressing_and_slipping(term), std::make_pair(n, 0));
  EXPECT_EQ(term.regime_changes(), (RegimeChanges{0, 0, n, n}));
  beams.evaluate(term, apart, 0.0);
  ASSERT_EQ(pressing_and_slipping(term), std::make_pair(0, 0));
  EXPECT_EQ(term.regime_changes(), (RegimeChanges{0, n, n, n}));
  beams.evaluate(term, pressed, 0.0);
  EXPECT_EQ(term.regime_changes(), (RegimeChanges{n, n, n, n}));
  beams.evaluate(term, pressed, 0.0);  // nothing changed
  EXPECT_EQ(term.regime_changes(), (RegimeChanges{n, n, n, n}));

  // A new detection that installs as many elements (here the same ones): its first evaluation is compared
  // with none, although the last one pressed and this one does not.
  beams.install(term);
  ASSERT_EQ(term.states().size(), beams.elements());
  beams.evaluate(term, apart, 0.0);
  EXPECT_EQ(term.regime_changes(), (RegimeChanges{n, n, n, n}));
  beams.evaluate(term, pressed, 0.0);
  EXPECT_EQ(term.regime_changes(), (RegimeChanges{2 * n, n, n, n}));

  // A reset (a new step attempt) zeroes the counts and forgets the last evaluation.
  term.reset_regime_changes();
  EXPECT_EQ(term.regime_changes(), RegimeChanges{});
  beams.evaluate(term, apart, 0.0);
  EXPECT_EQ(term.regime_changes(), RegimeChanges{});
  beams.evaluate(term, pressed, 0.0);
  EXPECT_EQ(term.regime_changes(), (RegimeChanges{n, 0, 0, 0}));

  // States restored from a saved run (set_elements, then set_states) are compared with none either.
  const std::vector<ContactState> saved = term.states();
  beams.install(term);
  term.set_states(saved);
  term.reset_regime_changes();
  beams.evaluate(term, apart, 0.0);
  EXPECT_EQ(term.regime_changes(), RegimeChanges{});
}

TEST(RegimeChanges, ADistributedEvaluationCountsWhenItsStatesAreShared) {
  // A rank that evaluates the elements of some blocks only (EquilibriumProblem::distribute) counts the
  // evaluation when the states of all the elements come back (set_states), as one process counts it.
  const ParallelBeams beams;
  const int n = static_cast<int>(beams.elements());
  ContactTerm term(beams.model), whole(beams.model);
  for (ContactTerm* t : {&term, &whole}) {
    t->set_laws(1e-3, std::nullopt);
    beams.install(*t);
    beams.evaluate(*t, 0.15, 0.0);
  }
  // The nodes of beam I up to x = 2.45 mm: a part of the elements (the overlap is x in [1, 4]).
  beams.evaluate(term, 0.19, 0.0, solver::BlockRange{0, 50});
  EXPECT_EQ(term.regime_changes(), RegimeChanges{});
  beams.evaluate(whole, 0.19, 0.0);
  ASSERT_EQ(whole.regime_changes(), (RegimeChanges{0, n, 0, 0}));
  term.set_states(whole.states());
  EXPECT_EQ(term.regime_changes(), whole.regime_changes());
}

}  // namespace
}  // namespace nodus::contact
