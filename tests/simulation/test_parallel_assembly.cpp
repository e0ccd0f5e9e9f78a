// Assembly on several threads gives bitwise the results of one thread (solver/ordered_assembly.hpp): the
// residual, every value of the tangent and the state of every contact element are compared with ==, not
// within a tolerance. The problem: four parallel beams on a square of side 1.99 R, each pressed into its two
// neighbours by 0.01 R, with friction, evaluated away from the committed (reference) state so that elements
// both stick and slip. It has enough beam and contact elements to go several times round the ring of buffers.

#include <gtest/gtest.h>

#include <omp.h>

#include <cstring>
#include <optional>
#include <random>
#include <vector>

#include <Eigen/Core>

#include "nodus/contact/detection.hpp"
#include "nodus/loading/boundary_conditions.hpp"
#include "nodus/model/model.hpp"
#include "nodus/simulation/equilibrium_problem.hpp"
#include "nodus/solver/ordered_assembly.hpp"

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
  for (int threads : {2, 3}) expect_identical(serial, bundle.evaluate(threads), threads);
  // Twice on the same thread count: the buffers kept across calls carry nothing over.
  expect_identical(serial, bundle.evaluate(1), 1);
  omp_set_num_threads(max_threads);
}

}  // namespace
}  // namespace nodus::simulation
