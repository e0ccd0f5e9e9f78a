// Assembly on several threads gives bitwise the results of one thread (solver/ordered_assembly.hpp): the
// residual, every value of the tangent and the state of every contact element are compared with ==, not
// within a tolerance. The problem: four parallel beams on a square of side 1.99 R, each pressed into its two
// neighbours by 0.01 R, with friction, evaluated away from the committed (reference) state so that elements
// both stick and slip. It has enough beam and contact elements to go several times round the ring of buffers.
// Then a whole run with friction on KLU, which uses no BLAS: its steps and final state do not depend on the
// number of threads either.

#include <gtest/gtest.h>

#include <omp.h>

#include <cstring>
#include <optional>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include <Eigen/Core>

#include "nodus/contact/detection.hpp"
#include "nodus/loading/boundary_conditions.hpp"
#include "nodus/model/model.hpp"
#include "nodus/scenario/scenario.hpp"
#include "nodus/simulation/equilibrium_problem.hpp"
#include "nodus/simulation/simulation.hpp"
#include "nodus/solver/ordered_assembly.hpp"
#include "nodus/solver/sparse_assembler.hpp"

namespace nodus::simulation {
namespace {

using Vec3 = Eigen::Vector3d;

constexpr double kRadius = 0.1;   // mm
constexpr double kLength = 10.0;  // mm
constexpr int kElements = 200;    // per beam

/// What one evaluation produced.
struct Evaluation {
  Eigen::VectorXd residual, full_residual;
  Eigen::VectorXd residual_alone;  ///< evaluated without the tangent
  std::vector<double> tangent;     ///< the values of the sparse tangent, in its storage order
  std::vector<contact::ContactState> contact;
};

/// The four beams, clamped at both ends, with contact and friction, evaluated at a perturbed state on
/// `threads` OpenMP threads.
class Bundle {
 public:
  Bundle() {
    const beam::ElasticConstants material{4000.0, 0.3};
    const double side = 1.99 * kRadius;
    const Vec3 corners[] = {{0, 0, 0}, {0, side, 0}, {0, side, side}, {0, 0, side}};
    for (int b = 0; b < 4; ++b)
      model_.add_beam(
          {"fibre", kLength, kRadius, kElements, corners[b], Vec3::UnitX(), Vec3::UnitY(), material, 1.0});
    const loading::DofMask all{true, true, true, true, true, true, true, true, true};
    for (int b = 0; b < 4; ++b)
      for (int node : {model_.beam(b).node(0), model_.beam(b).node(model_.beam(b).num_nodes() - 1)})
        conditions_.activate(conditions_.add_motion("clamp", node, all), 0.0, model_.reference());
    problem_.emplace(model_, conditions_, Tolerances{});
    contact::DetectionParameters given;
    given.self_contact = false;
    geometry_ = contact::detect(model_, model_.reference(), contact::resolve_parameters(given, model_, {}));
    problem_->set_contact(geometry_, std::vector<double>(geometry_.zones.size(), 400.0),
                          std::vector<Vec3>(geometry_.elements.size(), Vec3::Zero()));
    problem_->set_contact_laws(0.002, contact::FrictionLaw{0.3, 1e-4});
    problem_->set_time(0.0);
    problem_->commit();
    // Away from the committed state by up to 2 g_rev_max on centres: some elements stick, some slip.
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-2e-4, 2e-4);
    perturbed_ = problem_->unknowns();
    for (Eigen::Index i = 0; i < perturbed_.size(); ++i) perturbed_[i] += u(rng);
  }

  std::size_t contact_elements() const { return geometry_.elements.size(); }
  int beam_elements() const { return model_.num_elements(); }

  Evaluation evaluate(int threads) {
    omp_set_num_threads(threads);
    problem_->set_unknowns(perturbed_);
    Evaluation e;
    problem_->evaluate(e.residual, true);
    e.full_residual = problem_->full_residual();
    const solver::SparseMatrix& k = problem_->tangent();
    e.tangent.assign(k.valuePtr(), k.valuePtr() + k.nonZeros());
    e.contact = problem_->contact_states();
    problem_->evaluate(e.residual_alone, false);
    return e;
  }

 private:
  model::Model model_{2, 0.0};
  loading::Conditions conditions_;
  std::optional<EquilibriumProblem> problem_;
  contact::ContactGeometry geometry_;
  Eigen::VectorXd perturbed_;
};

/// Bitwise equality of two doubles (== would also hold for 0.0 and -0.0).
bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

void expect_identical(const Evaluation& a, const Evaluation& b, int threads) {
  ASSERT_EQ(a.residual.size(), b.residual.size());
  for (Eigen::Index i = 0; i < a.residual.size(); ++i)
    ASSERT_TRUE(same_bits(a.residual[i], b.residual[i])) << threads << " threads, residual " << i;
  for (Eigen::Index i = 0; i < a.residual.size(); ++i)
    ASSERT_TRUE(same_bits(a.residual_alone[i], b.residual_alone[i]))
        << threads << " threads, residual without tangent " << i;
  for (Eigen::Index i = 0; i < a.full_residual.size(); ++i)
    ASSERT_TRUE(same_bits(a.full_residual[i], b.full_residual[i])) << threads << " threads, reaction " << i;
  ASSERT_EQ(a.tangent.size(), b.tangent.size());
  for (std::size_t i = 0; i < a.tangent.size(); ++i)
    ASSERT_TRUE(same_bits(a.tangent[i], b.tangent[i])) << threads << " threads, tangent value " << i;
  ASSERT_EQ(a.contact.size(), b.contact.size());
  for (std::size_t k = 0; k < a.contact.size(); ++k) {
    const contact::ContactState &s = a.contact[k], &t = b.contact[k];
    ASSERT_TRUE(same_bits(s.gap, t.gap) && same_bits(s.normal_reaction, t.normal_reaction) &&
                s.tangential == t.tangential && s.reversible == t.reversible && s.slip == t.slip)
        << threads << " threads, contact element " << k;
  }
}

TEST(ParallelAssembly, ResidualAndTangentDoNotDependOnTheNumberOfThreads) {
  const int max_threads = omp_get_max_threads();
  Bundle bundle;
  // Both loops run on several threads and round their rings more than twice (else the comparison checks
  // nothing).
  omp_set_num_threads(2);
  const std::size_t contact_buffers = solver::assembly_buffers(bundle.contact_elements());
  const std::size_t beam_buffers = solver::assembly_buffers(static_cast<std::size_t>(bundle.beam_elements()));
  EXPECT_GT(contact_buffers, 1u);
  EXPECT_GT(beam_buffers, 1u);
  EXPECT_GT(bundle.contact_elements(), 2 * contact_buffers);
  EXPECT_GT(static_cast<std::size_t>(bundle.beam_elements()), 2 * beam_buffers);

  const Evaluation serial = bundle.evaluate(1);
  // Friction is at work, sticking and slipping, and the forces are not all zero.
  int slip = 0, stick = 0;
  for (const contact::ContactState& s : serial.contact)
    if (s.normal_reaction > 0.0) ++(s.slip ? slip : stick);
  EXPECT_GT(slip, 10);
  EXPECT_GT(stick, 10);
  EXPECT_GT(serial.residual.norm(), 0.0);
  // 4 and 7: more adders than this test's blocks of work per ring, and more threads than CI's cores.
  for (int threads : {2, 3, 4, 7}) expect_identical(serial, bundle.evaluate(threads), threads);
  // Twice on the same thread count: the buffers kept across calls carry nothing over.
  expect_identical(serial, bundle.evaluate(1), 1);
  omp_set_num_threads(max_threads);
}

TEST(ParallelAssembly, ARunOnKluDoesNotDependOnTheNumberOfThreads) {
  // A tool presses a rod of 300 elements on two supports and drags it with friction (the varying tangent,
  // not symmetric, on KLU): steps, iterations and the final state are compared bit for bit.
  const std::string text = R"(materials:
  - {name: nylon, young_modulus: 4000, poisson_ratio: 0.3}
beams:
  - {name: beam, material: nylon, radius: 0.1, length: 10, elements: 300, start: [-5, 0, 0],
     direction: [1, 0, 0], director1: [0, 1, 0]}
  - {name: tool, material: nylon, radius: 0.2, length: 2, elements: 4, start: [0, -1, 0.31],
     direction: [0, 1, 0], director1: [1, 0, 0]}
conditions:
  - {name: left, type: clamp, beam: beam, at: start, dofs: [position, g1z]}
  - {name: right, type: clamp, beam: beam, at: end, dofs: [y, z]}
  - {name: press, type: rigid, beam: tool}
stages:
  - {name: press, steps: 3, motions: {press: {translation: [0, 0, -0.1]}}}
  - {name: drag, steps: 4, motions: {press: {translation: [0, 0.3, -0.1]}}}
contact: {self_contact: false, friction: 0.3, friction_tangent: varying}
solver: {linear_solver: klu}
)";
  const int max_threads = omp_get_max_threads();
  const auto run = [&](int threads) {
    omp_set_num_threads(threads);
    Simulation sim(scenario::parse_scenario(text, "drag.yaml"));
    const RunSummary summary = sim.run({});
    EXPECT_TRUE(summary.converged) << summary.failure;
    return std::make_tuple(summary.steps, summary.newton_iterations, Eigen::VectorXd(sim.state()));
  };
  omp_set_num_threads(2);
  EXPECT_GT(solver::assembly_buffers(300), 1u);  // the beam's elements are assembled on both threads
  const auto one = run(1);
  for (int threads : {2, 3}) {
    const auto other = run(threads);
    EXPECT_EQ(std::get<0>(other), std::get<0>(one)) << threads << " threads";
    EXPECT_EQ(std::get<1>(other), std::get<1>(one)) << threads << " threads";
    ASSERT_EQ(std::get<2>(other).size(), std::get<2>(one).size());
    for (Eigen::Index i = 0; i < std::get<2>(one).size(); ++i)
      ASSERT_TRUE(same_bits(std::get<2>(other)[i], std::get<2>(one)[i]))
          << threads << " threads, unknown " << i;
  }
  omp_set_num_threads(max_threads);
}

// The threads' ranges of blocks (solver::SparseAssembler::split_columns): consecutive, covering every block
// once, each with about its share of the matrix's entries. A chain of 120 blocks of 9 unknowns, blocks 0 to 9
// also all coupled together (their columns much fuller), some unknowns prescribed.
TEST(ParallelAssembly, ColumnsSplitIntoConsecutiveRangesOfEqualWork) {
  constexpr int kBlocks = 120, kSize = 9;
  std::vector<std::vector<int>> groups;
  for (int b = 0; b + 1 < kBlocks; ++b) groups.push_back({b, b + 1});
  groups.emplace_back();
  for (int b = 0; b < 10; ++b) groups.back().push_back(b);
  std::vector<int> free_index(kBlocks * kSize);
  for (int i = 0, row = 0; i < kBlocks * kSize; ++i)
    free_index[static_cast<std::size_t>(i)] = i % 7 == 3 ? -1 : row++;
  const solver::SparseAssembler assembler(kSize, free_index, groups);
  const solver::SparseMatrix& a = assembler.matrix();
  // Entries in the columns of blocks [first, last).
  const auto entries = [&](int first, int last) {
    long long n = 0;
    for (int dof = first * kSize; dof < std::min(last, kBlocks) * kSize; ++dof)
      if (const int col = free_index[static_cast<std::size_t>(dof)]; col >= 0)
        n += a.outerIndexPtr()[col + 1] - a.outerIndexPtr()[col];
    return n;
  };
  const long long total = entries(0, kBlocks);
  ASSERT_EQ(total, a.nonZeros());
  long long fullest = 0;
  for (int b = 0; b < kBlocks; ++b) fullest = std::max(fullest, entries(b, b + 1));
  for (int parts : {1, 2, 3, 4, 7, 16}) {
    const std::vector<solver::BlockRange> ranges = assembler.split_columns(parts);
    ASSERT_EQ(ranges.size(), static_cast<std::size_t>(parts));
    EXPECT_EQ(ranges.front().first, 0);
    EXPECT_GE(ranges.back().last, kBlocks);  // open-ended
    for (std::size_t p = 0; p < ranges.size(); ++p) {
      if (p > 0) {
        EXPECT_EQ(ranges[p].first, ranges[p - 1].last) << parts << " parts";
      }
      EXPECT_LE(ranges[p].first, ranges[p].last) << parts << " parts";
      // Within one block's entries (and its one count) of an equal share.
      EXPECT_NEAR(static_cast<double>(entries(ranges[p].first, ranges[p].last)),
                  static_cast<double>(total) / parts, static_cast<double>(fullest + kBlocks / parts + 1))
          << parts << " parts, range " << p;
    }
  }
  // Without a tangent the blocks are split by their number.
  const std::vector<solver::BlockRange> even = solver::even_split(10, 4);
  ASSERT_EQ(even.size(), 4u);
  EXPECT_EQ(even[0].first, 0);
  EXPECT_EQ(even[1].first, 2);
  EXPECT_EQ(even[2].first, 5);
  EXPECT_EQ(even[3].first, 7);
  EXPECT_TRUE(even[3].contains(1000));
}

// A rank of a distributed run holds and assembles the rows of its own blocks only (SparseAssembler's `rows`):
// each rank's entries are bitwise those of the whole assembly, in its rows only, and the ranks' rows together
// are the whole matrix. The ranks' blocks are balanced by the entries of their columns, which split_blocks
// counts from the adjacency as split_columns counts them in the whole matrix.
TEST(ParallelAssembly, EachRanksRowsAreThoseOfTheWholeMatrix) {
  constexpr int kBlocks = 40, kSize = 9;
  std::vector<std::vector<int>> groups;
  for (int b = 0; b + 2 < kBlocks; b += 2) groups.push_back({b, b + 1, b + 2});
  for (int b = 0; b + 7 < kBlocks; b += 3) groups.push_back({b, b + 7});  // contact-like couplings
  std::vector<int> free_index(kBlocks * kSize);
  for (int i = 0, row = 0; i < kBlocks * kSize; ++i)
    free_index[static_cast<std::size_t>(i)] = i % 5 == 2 ? -1 : row++;
  std::vector<int> offsets;
  for (int b = 0; b <= kBlocks; ++b) offsets.push_back(b * kSize);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::MatrixXd> blocks;
  for (const std::vector<int>& g : groups) {
    const auto m = static_cast<Eigen::Index>(g.size()) * kSize;
    blocks.push_back(Eigen::MatrixXd::NullaryExpr(m, m, [&] { return u(rng); }));
  }
  // Each group added twice, so that entries are sums.
  const auto assemble = [&](solver::SparseAssembler& a) {
    a.set_zero();
    for (int pass = 0; pass < 2; ++pass)
      for (std::size_t k = 0; k < groups.size(); ++k) a.add(groups[k], blocks[k]);
  };
  solver::SparseAssembler whole(kSize, free_index, groups);
  assemble(whole);
  const solver::SparseMatrix& w = whole.matrix();
  const solver::BlockAdjacency adjacency = solver::block_adjacency(kBlocks, groups);
  const std::vector<solver::BlockRange> ranks = solver::split_blocks(offsets, free_index, adjacency, 3);
  const std::vector<solver::BlockRange>& by_columns = whole.split_columns(3);
  ASSERT_EQ(ranks.size(), 3U);
  ASSERT_EQ(by_columns.size(), 3U);
  for (std::size_t r = 0; r < ranks.size(); ++r) {
    EXPECT_EQ(ranks[r].first, by_columns[r].first);
    EXPECT_EQ(ranks[r].last, by_columns[r].last);
  }
  EXPECT_GT(ranks[1].first, 0);
  EXPECT_GT(ranks[2].first, ranks[1].first);
  // The block of each free row.
  std::vector<int> block_of_row;
  for (int i = 0; i < kBlocks * kSize; ++i)
    if (free_index[static_cast<std::size_t>(i)] >= 0) block_of_row.push_back(i / kSize);
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(w.rows(), w.cols());
  Eigen::Index entries = 0;
  for (const solver::BlockRange& rows : ranks) {
    solver::SparseAssembler part(offsets, free_index, adjacency, rows);
    assemble(part);
    const solver::SparseMatrix& p = part.matrix();
    entries += p.nonZeros();
    for (Eigen::Index c = 0; c < p.outerSize(); ++c)
      for (solver::SparseMatrix::InnerIterator it(p, c); it; ++it) {
        ASSERT_TRUE(rows.contains(block_of_row[static_cast<std::size_t>(it.row())])) << "row " << it.row();
        ASSERT_TRUE(same_bits(it.value(), w.coeff(it.row(), c))) << "row " << it.row() << ", column " << c;
      }
    sum += Eigen::MatrixXd(p);
  }
  EXPECT_EQ(entries, w.nonZeros());
  EXPECT_EQ(sum, Eigen::MatrixXd(w));
}

}  // namespace
}  // namespace nodus::simulation
