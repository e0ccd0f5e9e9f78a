// Load stepping (solver/load_stepping.hpp) on a toy problem: two uncoupled hardening springs
// u_i + c_i u_i^3 = F_i t. The rules are checked against what load_stepping.cpp states, with a scripted step
// solver whose success and iteration count are chosen per attempt (from the committed time and the step size
// only, so that a resumed run sees the same answers):
//  - cutback: a failed step is restored and halved, up to max_cutbacks, then the stepping fails with one line
//    naming the step and the cutbacks;
//  - growth: after a step converged in at most easy_iterations Newton iterations (the longest single solve
//    when the step needed several) and without cutback, the next step is growth times larger, never beyond
//    the nominal step;
//  - sliver: a step within 1 % of the remainder of the interval (or longer than it) takes all of it;
//  - secant predictor: each step starts from the linear extrapolation of the last converged step;
//  - resumption: advance() stopped after a step and continued from its StepperState gives the same steps;
//  - the step solver sees the halvings of the attempt so far (StepperState::cutbacks), 0 between steps;
//  - each converged step carries its size and the failure messages of its own cutbacks.
// And with the real Newton solver, whose iterations (at most 6 here) do not suffice for a large step of the
// hardening springs, the cutbacks take the stepping through and the end state solves the springs.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "nodus/solver/linear_solver.hpp"
#include "nodus/solver/load_stepping.hpp"
#include "nodus/solver/newton.hpp"

namespace nodus::solver {
namespace {

/// Two hardening springs u_i + c_i u_i^3 = F_i t (u [mm], F [N], unit stiffness [N/mm], c [N/mm^3]).
class Springs final : public SteppedProblem {
 public:
  Springs() : u_(Eigen::VectorXd::Zero(2)), committed_(Eigen::VectorXd::Zero(2)), k_(2, 2) {
    k_.insert(0, 0) = 1.0;
    k_.insert(1, 1) = 1.0;
    k_.makeCompressed();
  }
  static constexpr double kC[2] = {1.0, 3.0};
  static constexpr double kF[2] = {10.0, 4.0};

  int size() const override { return 2; }
  Eigen::VectorXd unknowns() const override { return u_; }
  void set_unknowns(const Eigen::VectorXd& u) override { u_ = u; }
  void evaluate(Eigen::VectorXd& r, bool with_tangent) override {
    r.resize(2);
    for (int i = 0; i < 2; ++i) {
      r[i] = u_[i] + kC[i] * u_[i] * u_[i] * u_[i] - kF[i] * time_;
      if (with_tangent) k_.coeffRef(i, i) = 1.0 + 3.0 * kC[i] * u_[i] * u_[i];
    }
  }
  const SparseMatrix& tangent() const override { return k_; }
  double residual_tolerance() const override { return 1e-10; }
  double scaled_increment(const Eigen::VectorXd& du) const override { return du.lpNorm<Eigen::Infinity>(); }
  double increment_tolerance() const override { return 1e-8; }

  void set_time(double t) override { time_ = t; }
  void commit() override {
    committed_ = u_;
    committed_time_ = time_;
    ++commits;
  }
  void restore() override {
    u_ = committed_;
    time_ = committed_time_;
    ++restores;
  }

  double time() const { return time_; }
  double committed_time() const { return committed_time_; }
  /// The exact equilibrium at load time t (scalar Newton from u = F t^(1/3) / c^(1/3), converged to
  /// round-off).
  static Eigen::VectorXd solution(double t) {
    Eigen::VectorXd u(2);
    for (int i = 0; i < 2; ++i) {
      double x = std::cbrt(kF[i] * t / kC[i]);
      for (int it = 0; it < 100; ++it) {
        const double dx = (x + kC[i] * x * x * x - kF[i] * t) / (1.0 + 3.0 * kC[i] * x * x);
        x -= dx;
        if (std::abs(dx) <= 1e-16 * std::max(1.0, std::abs(x))) break;
      }
      u[i] = x;
    }
    return u;
  }

  int commits = 0;
  int restores = 0;

 private:
  Eigen::VectorXd u_, committed_;
  double time_ = 0.0, committed_time_ = 0.0;
  SparseMatrix k_;
};

/// One attempt of the scripted solver: where it started.
struct Attempt {
  double from;  ///< committed load time
  double step;  ///< attempted step
  Eigen::VectorXd start;
  bool converged;
};

/// A step solver whose outcome is scripted from (committed time, step): `fails` says whether the attempt
/// fails, `iterations` how many Newton iterations a converged one reports. A converged attempt leaves the
/// problem at the exact solution.
struct ScriptedSolver {
  std::function<bool(double from, double step)> fails = [](double, double) { return false; };
  std::function<int(double from, double step)> iterations = [](double, double) { return 2; };
  int longest_solve = 0;
  std::vector<Attempt> attempts;

  StepSolver solver() {
    return [this](SteppedProblem& p) {
      auto& s = dynamic_cast<Springs&>(p);
      const double from = s.committed_time(), step = s.time() - s.committed_time();
      NewtonReport report;
      const bool fail = fails(from, step);
      attempts.push_back({from, step, s.unknowns(), !fail});
      if (fail) {
        report.iterations = 25;
        report.failure = "scripted failure";
        // What a failed Newton leaves behind: garbage the stepper must restore.
        s.set_unknowns(Eigen::VectorXd::Constant(2, 1e6));
        return report;
      }
      s.set_unknowns(Springs::solution(s.time()));
      report.converged = true;
      report.iterations = iterations(from, step);
      report.longest_solve = longest_solve;
      return report;
    };
  }
};

/// Runs advance() from t0 to t1 and returns the converged steps.
std::vector<StepResult> run(Springs& p, ScriptedSolver& solver, double t0, double t1, const StepControl& c,
                            AdvanceResult* result = nullptr) {
  std::vector<StepResult> steps;
  const AdvanceResult r =
      advance(p, solver.solver(), t0, t1, c, [&](const StepResult& s) { steps.push_back(s); });
  if (result) *result = r;
  return steps;
}

TEST(LoadStepping, CutbackHalvesAFailedStepAndRestores) {
  Springs p;
  ScriptedSolver solver;
  solver.fails = [](double, double step) { return step > 0.3; };
  solver.iterations = [](double, double) { return 10; };  // not easy: no growth
  StepControl c;
  c.nominal_step = 1.0;
  AdvanceResult result;
  const std::vector<StepResult> steps = run(p, solver, 0.0, 1.0, c, &result);
  ASSERT_TRUE(result.completed) << result.failure;
  // Attempts: 1 and 0.5 fail, 0.25 converges (2 cutbacks); the steps are not easy, so 0.25 four times.
  ASSERT_EQ(solver.attempts.size(), 6u);
  const std::vector<double> expected{1.0, 0.5, 0.25, 0.25, 0.25, 0.25};
  for (std::size_t k = 0; k < expected.size(); ++k) EXPECT_EQ(solver.attempts[k].step, expected[k]) << k;
  EXPECT_EQ(p.restores, 2);
  ASSERT_EQ(steps.size(), 4u);
  EXPECT_EQ(steps[0].cutbacks, 2);
  for (std::size_t k = 1; k < 4; ++k) EXPECT_EQ(steps[k].cutbacks, 0);
  // The failed attempts left garbage; the retried ones started from the committed state (here the start of
  // the interval, no predictor yet).
  EXPECT_EQ(solver.attempts[1].start, Eigen::VectorXd::Zero(2));
  EXPECT_EQ(solver.attempts[2].start, Eigen::VectorXd::Zero(2));
  EXPECT_EQ(steps.back().time, 1.0);
  EXPECT_LT((p.unknowns() - Springs::solution(1.0)).norm(), 1e-14);
  // Each step says its size, and why its failed attempts failed (the step solver's failure), in order.
  for (const StepResult& s : steps) EXPECT_EQ(s.step, 0.25);
  EXPECT_EQ(steps[0].cutback_causes, (std::vector<std::string>{"scripted failure", "scripted failure"}));
  for (std::size_t k = 1; k < 4; ++k) EXPECT_TRUE(steps[k].cutback_causes.empty()) << k;
}

TEST(LoadStepping, EachStepCarriesTheCausesOfItsOwnCutbacks) {
  // Steps of 0.25 (no growth) over [0, 0.5]; an attempt fails beyond 0.125 except from the start, with a
  // message naming its size (and holding commas): the first step converges at once, the second after one
  // cutback to 0.125, the third (0.125, what is left) at once, its causes not carried over from the second.
  Springs p;
  ScriptedSolver solver;
  solver.fails = [](double from, double step) { return from > 0.0 && step > 0.125; };
  StepControl c;
  c.nominal_step = 0.25;
  c.growth = 1.0;
  std::vector<StepResult> steps;
  const StepSolver scripted = solver.solver();
  const AdvanceResult result = advance(
      p,
      [&](SteppedProblem& problem) {
        const auto& springs = dynamic_cast<Springs&>(problem);
        const double step = springs.time() - springs.committed_time();
        NewtonReport r = scripted(problem);
        if (!r.converged) r.failure = "step of " + std::to_string(step) + ", at 1, 2";
        return r;
      },
      0.0, 0.5, c, [&](const StepResult& s) { steps.push_back(s); });
  ASSERT_TRUE(result.completed) << result.failure;
  ASSERT_EQ(steps.size(), 3u);
  EXPECT_EQ(steps[0].step, 0.25);
  EXPECT_TRUE(steps[0].cutback_causes.empty());
  EXPECT_EQ(steps[1].cutbacks, 1);
  EXPECT_EQ(steps[1].step, 0.125);
  EXPECT_EQ(steps[1].cutback_causes, std::vector<std::string>{"step of 0.250000, at 1, 2"});
  EXPECT_EQ(steps[2].cutbacks, 0);
  EXPECT_EQ(steps[2].step, 0.125);
  EXPECT_TRUE(steps[2].cutback_causes.empty());
}

TEST(LoadStepping, GivesUpAfterMaxCutbacksWithOneLine) {
  Springs p;
  ScriptedSolver solver;
  solver.fails = [](double, double) { return true; };
  StepControl c;
  c.nominal_step = 1.0;
  c.max_cutbacks = 3;
  AdvanceResult result;
  const std::vector<StepResult> steps = run(p, solver, 0.0, 2.0, c, &result);
  EXPECT_FALSE(result.completed);
  EXPECT_FALSE(result.stopped);
  EXPECT_EQ(result.steps, 0);
  EXPECT_TRUE(steps.empty());
  ASSERT_EQ(solver.attempts.size(), 4u);  // 1, 1/2, 1/4, 1/8: the first try and three cutbacks
  EXPECT_EQ(solver.attempts.back().step, 0.125);
  EXPECT_EQ(p.restores, 4);
  EXPECT_EQ(p.commits, 0);
  EXPECT_EQ(result.failure, "step from load time 0 to 0.125 failed after 3 cutbacks: scripted failure");
  EXPECT_EQ(p.unknowns(), Eigen::VectorXd::Zero(2)) << "left at the committed state";
}

TEST(LoadStepping, EasyStepsGrowUpToTheNominalStep) {
  Springs p;
  ScriptedSolver solver;  // every step converges in 2 iterations: easy
  StepControl c;
  c.nominal_step = 0.5;
  StepperState state = start_stepping(0.0, 3.0, c);
  EXPECT_EQ(state.step, 0.5);
  state.step = 0.05;  // as after cutbacks
  std::vector<double> sizes;
  const AdvanceResult r = advance(p, solver.solver(), 3.0, c, state, [&](const StepResult& s) {
    sizes.push_back(s.step);
    return true;
  });
  ASSERT_TRUE(r.completed);
  // Doubling from 0.05, capped at 0.5 (0.4 would give 0.8), then the remainder 0.25 at the end.
  const std::vector<double> expected{0.05, 0.1, 0.2, 0.4, 0.5, 0.5, 0.5, 0.5, 0.25};
  ASSERT_EQ(sizes.size(), expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) EXPECT_NEAR(sizes[k], expected[k], 1e-15) << k;
}

TEST(LoadStepping, HardStepsAndStepsAfterACutbackDoNotGrow) {
  StepControl c;
  c.nominal_step = 1.0;
  c.easy_iterations = 4;
  {  // 5 iterations: not easy
    Springs p;
    ScriptedSolver solver;
    solver.iterations = [](double, double) { return 5; };
    StepperState state = start_stepping(0.0, 1.0, c);
    state.step = 0.25;
    advance(p, solver.solver(), 1.0, c, state, [](const StepResult&) { return true; });
    ASSERT_EQ(solver.attempts.size(), 4u);
    for (const Attempt& a : solver.attempts) EXPECT_EQ(a.step, 0.25);
  }
  {  // 20 iterations summed over several solves, the longest of 4: easy
    Springs p;
    ScriptedSolver solver;
    solver.iterations = [](double, double) { return 20; };
    solver.longest_solve = 4;
    StepperState state = start_stepping(0.0, 1.0, c);
    state.step = 0.25;
    advance(p, solver.solver(), 1.0, c, state, [](const StepResult&) { return true; });
    ASSERT_EQ(solver.attempts.size(), 3u);  // 0.25, 0.5, then the remainder 0.25
    EXPECT_EQ(solver.attempts[1].step, 0.5);
  }
  {  // 8 iterations summed, the longest solve of 5: not easy
    Springs p;
    ScriptedSolver solver;
    solver.iterations = [](double, double) { return 8; };
    solver.longest_solve = 5;
    StepperState state = start_stepping(0.0, 1.0, c);
    state.step = 0.25;
    advance(p, solver.solver(), 1.0, c, state, [](const StepResult&) { return true; });
    ASSERT_EQ(solver.attempts.size(), 4u);
    for (const Attempt& a : solver.attempts) EXPECT_EQ(a.step, 0.25);
  }
  {  // easy (1 iteration) but after a cutback: the next attempt keeps the halved size, then grows
    Springs p;
    ScriptedSolver solver;
    solver.fails = [](double from, double step) { return from == 0.0 && step > 0.5; };
    solver.iterations = [](double, double) { return 1; };
    advance(p, solver.solver(), 0.0, 2.0, c, [](const StepResult&) {});
    ASSERT_GE(solver.attempts.size(), 4u);
    EXPECT_EQ(solver.attempts[0].step, 1.0);
    EXPECT_EQ(solver.attempts[1].step, 0.5);
    EXPECT_EQ(solver.attempts[2].step, 0.5) << "no growth right after a cutback";
    EXPECT_EQ(solver.attempts[3].step, 1.0) << "growth after an easy step without cutback";
  }
}

TEST(LoadStepping, ASliverAtTheEndIsMergedIntoTheLastStep) {
  StepControl c;
  c.nominal_step = 0.3;
  {  // remainder 0.302 after the first step: 0.3 >= 0.99 * 0.302, so one step of 0.302, not 0.3 + 0.002
    Springs p;
    ScriptedSolver solver;
    solver.iterations = [](double, double) { return 10; };  // no growth
    const auto steps = run(p, solver, 0.0, 0.602, c);
    ASSERT_EQ(steps.size(), 2u);
    EXPECT_EQ(steps[0].step, 0.3);
    EXPECT_NEAR(steps[1].step, 0.302, 1e-15);
    EXPECT_EQ(steps[1].time, 0.602) << "lands exactly on t1";
  }
  {  // remainder 0.31: 0.3 < 0.99 * 0.31, so the 0.01 is a step of its own
    Springs p;
    ScriptedSolver solver;
    solver.iterations = [](double, double) { return 10; };
    const auto steps = run(p, solver, 0.0, 0.61, c);
    ASSERT_EQ(steps.size(), 3u);
    EXPECT_EQ(steps[1].step, 0.3);
    EXPECT_NEAR(steps[2].step, 0.01, 1e-15);
    EXPECT_EQ(steps[2].time, 0.61);
  }
  {  // a step longer than the remainder is cut to it
    Springs p;
    ScriptedSolver solver;
    solver.iterations = [](double, double) { return 10; };
    const auto steps = run(p, solver, 0.0, 0.5, c);
    ASSERT_EQ(steps.size(), 2u);
    EXPECT_NEAR(steps[1].step, 0.2, 1e-15);
    EXPECT_EQ(steps[1].time, 0.5);
  }
  {  // an interval shorter than the nominal step is one step
    Springs p;
    ScriptedSolver solver;
    const auto steps = run(p, solver, 1.0, 1.1, c);
    ASSERT_EQ(steps.size(), 1u);
    EXPECT_NEAR(steps[0].step, 0.1, 1e-15);
  }
}

TEST(LoadStepping, SecantPredictorExtrapolatesTheLastStep) {
  Springs p;
  ScriptedSolver solver;
  // Steps of 0.2 (not easy, no growth), and a failure at the third to see the predictor after a cutback.
  solver.iterations = [](double, double) { return 10; };
  solver.fails = [](double from, double step) { return std::abs(from - 0.4) < 1e-12 && step > 0.15; };
  StepControl c;
  c.nominal_step = 0.2;
  run(p, solver, 0.0, 1.0, c);
  ASSERT_GE(solver.attempts.size(), 5u);
  // First step: no predictor, starts at the committed (initial) state.
  EXPECT_EQ(solver.attempts[0].start, Eigen::VectorXd::Zero(2));
  int checked = 0;
  for (std::size_t k = 1; k < solver.attempts.size(); ++k) {
    const Attempt& a = solver.attempts[k];
    // The last converged step before this attempt: from t_a to t_b = a.from (exact solutions at both).
    const Attempt* last = nullptr;
    for (std::size_t j = k; j-- > 0;)
      if (solver.attempts[j].converged) {
        last = &solver.attempts[j];
        break;
      }
    ASSERT_NE(last, nullptr);
    const Eigen::VectorXd u_a = Springs::solution(last->from);
    const Eigen::VectorXd u_b = Springs::solution(a.from);
    const Eigen::VectorXd predicted = u_b + (a.step / last->step) * (u_b - u_a);
    EXPECT_LT((a.start - predicted).norm(), 1e-14) << "attempt " << k;
    // The prediction is not the solution: the springs are nonlinear.
    EXPECT_GT((a.start - Springs::solution(a.from + a.step)).norm(), 1e-6);
    ++checked;
  }
  EXPECT_EQ(checked, static_cast<int>(solver.attempts.size()) - 1);
  // One of them was a retry after a cutback, extrapolating by half the last step.
  bool retried = false;
  for (const Attempt& a : solver.attempts)
    retried = retried || (std::abs(a.from - 0.4) < 1e-12 && std::abs(a.step - 0.1) < 1e-12);
  EXPECT_TRUE(retried);
}

/// The real Newton solver, at most 6 iterations without line search: steps of the hardening springs longer
/// than a few tenths fail, and the stepping cuts back and grows.
struct RealNewton {
  std::unique_ptr<LinearSolver> linear = make_linear_solver(LinearSolverKind::umfpack);
  NewtonSolver newton{*linear, NewtonSettings{6, false, 6, 0.5, {}}};
  StepSolver solver() {
    return [this](SteppedProblem& p) { return newton.solve(p); };
  }
};

TEST(LoadStepping, NewtonFailuresAreCutBackAndTheEndStateSolvesTheSprings) {
  Springs p;
  RealNewton newton;
  StepControl c;
  c.nominal_step = 4.0;
  c.easy_iterations = 4;
  std::vector<StepResult> steps;
  const AdvanceResult r =
      advance(p, newton.solver(), 0.0, 10.0, c, [&](const StepResult& s) { steps.push_back(s); });
  ASSERT_TRUE(r.completed) << r.failure;
  int cutbacks = 0;
  for (const StepResult& s : steps) {
    cutbacks += s.cutbacks;
    EXPECT_LE(s.step, c.nominal_step);
    EXPECT_TRUE(s.newton.converged);
  }
  EXPECT_GT(cutbacks, 0) << "the first nominal step (0 to 4) is too large for 6 iterations";
  EXPECT_LT((p.unknowns() - Springs::solution(10.0)).norm(), 1e-9);
}

TEST(LoadStepping, ResumedSteppingTakesTheSameSteps) {
  StepControl c;
  c.nominal_step = 4.0;
  c.easy_iterations = 4;
  // Uninterrupted.
  std::vector<StepResult> whole;
  Eigen::VectorXd end_whole;
  {
    Springs p;
    RealNewton newton;
    StepperState state = start_stepping(0.0, 10.0, c);
    const AdvanceResult r = advance(p, newton.solver(), 10.0, c, state, [&](const StepResult& s) {
      whole.push_back(s);
      return true;
    });
    ASSERT_TRUE(r.completed) << r.failure;
    end_whole = p.unknowns();
  }
  ASSERT_GE(whole.size(), 4u);
  // The run exercises what the state carries: cutbacks (6 at the first step), growth (0.0625 to 2), the
  // predictor, and the end of the interval.
  EXPECT_GT(whole.front().cutbacks, 0);
  EXPECT_GT(whole.back().step, 2 * whole.front().step);
  // Stopped after each possible step k, then continued in a fresh problem and solver from the saved state
  // (as a saved run resumed: the committed unknowns and the StepperState).
  for (std::size_t stop = 1; stop < whole.size(); ++stop) {
    std::vector<StepResult> resumed;
    StepperState saved;
    Eigen::VectorXd committed;
    {
      Springs p;
      RealNewton newton;
      StepperState state = start_stepping(0.0, 10.0, c);
      const AdvanceResult r = advance(p, newton.solver(), 10.0, c, state, [&](const StepResult& s) {
        resumed.push_back(s);
        return resumed.size() < stop;
      });
      ASSERT_TRUE(r.stopped);
      EXPECT_FALSE(r.completed);
      saved = state;
      committed = p.unknowns();
    }
    Springs p;
    p.set_unknowns(committed);
    p.set_time(saved.time);
    p.commit();
    RealNewton newton;
    const AdvanceResult r = advance(p, newton.solver(), 10.0, c, saved, [&](const StepResult& s) {
      resumed.push_back(s);
      return true;
    });
    ASSERT_TRUE(r.completed) << r.failure;
    ASSERT_EQ(resumed.size(), whole.size()) << "stopped after " << stop;
    for (std::size_t k = 0; k < whole.size(); ++k) {
      EXPECT_EQ(resumed[k].time, whole[k].time) << "stop " << stop << " step " << k;
      EXPECT_EQ(resumed[k].step, whole[k].step);
      EXPECT_EQ(resumed[k].cutbacks, whole[k].cutbacks);
      EXPECT_EQ(resumed[k].newton.iterations, whole[k].newton.iterations);
    }
    EXPECT_EQ(p.unknowns(), end_whole) << "bit for bit";
  }
}

TEST(LoadStepping, TheSolverSeesTheCutbacksOfItsAttempt) {
  // Every attempt fails but the last one allowed (max_cutbacks 3): the solver, which reads the stepper's
  // cutbacks, sees 0, 1, 2, 3, and the step of 1/8 converges; the stepping stopped there, the state reads 0.
  Springs p;
  ScriptedSolver scripted;
  const StepSolver inner = scripted.solver();
  StepControl c;
  c.nominal_step = 1.0;
  c.max_cutbacks = 3;
  StepperState state = start_stepping(0.0, 1.0, c);
  std::vector<int> seen;
  scripted.fails = [&](double, double) { return state.cutbacks < c.max_cutbacks; };
  const StepSolver solve = [&](SteppedProblem& q) {
    seen.push_back(state.cutbacks);
    return inner(q);
  };
  AdvanceResult r = advance(p, solve, 1.0, c, state, [](const StepResult&) { return false; });
  ASSERT_TRUE(r.stopped);
  EXPECT_EQ(seen, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(state.time, 0.125);
  EXPECT_EQ(state.cutbacks, 0);
  // A step that fails for good leaves 0 too.
  scripted.fails = [](double, double) { return true; };
  r = advance(p, solve, 1.0, c, state, [](const StepResult&) { return true; });
  EXPECT_FALSE(r.completed);
  EXPECT_NE(r.failure.find("failed after 3 cutbacks"), std::string::npos) << r.failure;
  EXPECT_EQ(state.cutbacks, 0);
}

}  // namespace
}  // namespace nodus::solver
