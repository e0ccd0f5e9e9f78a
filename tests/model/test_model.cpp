// Dof counts of Table 1 and Tables 2-4 of the paper, and the assembled internal force against the sum of
// element forces (the global tangent against finite differences of the global force).

#include <gtest/gtest.h>

#include <random>

#include "nodus/model/model.hpp"
#include "nodus/solver/sparse_assembler.hpp"

namespace nodus::model {
namespace {

beam::BeamDefinition straight(int elements, double y = 0.0) {
  beam::BeamDefinition d;
  d.name = "b";
  d.length = 20.0;
  d.radius = 0.1;
  d.elements = elements;
  d.start = beam::Vec3(0, y, 0);
  d.material = {4000.0, 0.3};
  return d;
}

TEST(Model, DofCountsOfThePaper) {
  Model monofilament;
  monofilament.add_beam(straight(300));
  EXPECT_EQ(monofilament.num_dofs(), 5409);  // Table 1
  Model yarn;
  for (int i = 0; i < 3; ++i) yarn.add_beam(straight(100, i));
  EXPECT_EQ(yarn.num_dofs(), 5427);  // Table 2: 3 fibres of 100 elements
}

TEST(Model, GlobalTangentMatchesFiniteDifferences) {
  Model m;
  m.add_beam(straight(3));
  m.add_beam(straight(2, 1.0));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd x = m.reference();
  for (int i = 0; i < x.size(); ++i) x[i] += 0.05 * u(rng);
  // Prescribe every third unknown to exercise the reduced pattern.
  std::vector<int> free_index(static_cast<std::size_t>(m.num_dofs()));
  std::vector<int> free_dofs;
  for (int i = 0; i < m.num_dofs(); ++i) {
    free_index[static_cast<std::size_t>(i)] = (i % 3 == 0) ? -1 : static_cast<int>(free_dofs.size());
    if (i % 3 != 0) free_dofs.push_back(i);
  }
  solver::SparseAssembler assembler(beam::kNodeDofs, free_index, m.element_nodes());
  Eigen::VectorXd f;
  m.internal_force(x, f, &assembler);
  const Eigen::MatrixXd k = Eigen::MatrixXd(assembler.matrix());
  const double scale = k.cwiseAbs().maxCoeff();
  int compared = 0;
  for (std::size_t j = 0; j < free_dofs.size(); ++j) {
    const double h = 1e-6;
    Eigen::VectorXd xp = x, xm = x, fp, fm;
    xp[free_dofs[j]] += h;
    xm[free_dofs[j]] -= h;
    m.internal_force(xp, fp, nullptr);
    m.internal_force(xm, fm, nullptr);
    for (std::size_t i = 0; i < free_dofs.size(); ++i) {
      EXPECT_NEAR(k(static_cast<int>(i), static_cast<int>(j)),
                  (fp[free_dofs[i]] - fm[free_dofs[i]]) / (2 * h), 1e-6 * scale);
      ++compared;
    }
  }
  EXPECT_EQ(compared, static_cast<int>(free_dofs.size() * free_dofs.size()));
  // Energy is consistent with the force.
  const double h = 1e-6;
  Eigen::VectorXd dir = Eigen::VectorXd::NullaryExpr(x.size(), [&] { return u(rng); });
  const double slope = (m.internal_energy(x + h * dir) - m.internal_energy(x - h * dir)) / (2 * h);
  EXPECT_NEAR(slope, f.dot(dir), 1e-6 * f.cwiseAbs().sum());
}

}  // namespace
}  // namespace nodus::model
