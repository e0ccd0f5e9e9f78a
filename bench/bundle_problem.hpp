#pragma once
// The 27- or 75-fibre twisted bundle of twisted_bundle.hpp as an equilibrium problem with contact: both ends
// of every fibre held, the contact elements of one detection installed with a zone penalty of 400 (every
// element pressing). Shared by bench_contact_newton and bench_mpi_solve.

#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "nodus/contact/detection.hpp"
#include "nodus/loading/boundary_conditions.hpp"
#include "nodus/simulation/equilibrium_problem.hpp"
#include "twisted_bundle.hpp"

namespace nodus::bench {

struct Setup {
  bench::Bundle bundle;
  loading::Conditions conditions;
  std::unique_ptr<simulation::EquilibriumProblem> problem;
  contact::ContactGeometry geometry;

  explicit Setup(int fibres) : bundle(twisted_bundle(fibres, 100, 10.0, 0.1, 1.99)) {
    const model::Model& model = bundle.model;
    const loading::DofMask all{true, true, true, true, true, true, true, true, true};
    for (int f = 0; f < fibres; ++f) {
      const beam::Beam& beam = model.beam(f);
      for (int node : {beam.node(0), beam.node(beam.num_nodes() - 1)})
        conditions.activate(conditions.add_motion("end", node, all), 0.0, bundle.x);
    }
    problem = std::make_unique<simulation::EquilibriumProblem>(model, conditions, simulation::Tolerances{});
    problem->set_time(0.0);
    const std::vector<bool> prescribed = conditions.prescribed(model.num_dofs());
    Eigen::VectorXd u(problem->size());
    for (int i = 0, k = 0; i < model.num_dofs(); ++i)
      if (!prescribed[static_cast<std::size_t>(i)]) u[k++] = bundle.x[i];
    problem->set_unknowns(u);
    geometry = contact::detect(model, bundle.x, {});
    // The default laws of a run: k0 = E R, p_max = 0.02 R, p_reg = p_max / 10.
    problem->set_contact_laws(0.0002, std::nullopt);
    problem->set_contact(geometry, std::vector<double>(geometry.zones.size(), 400.0),
                         std::vector<Eigen::Vector3d>(geometry.elements.size(), Eigen::Vector3d::Zero()));
  }
};

}  // namespace nodus::bench
