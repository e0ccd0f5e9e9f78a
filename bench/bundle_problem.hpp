#pragma once
// The 27- or 75-fibre twisted bundle of twisted_bundle.hpp as an equilibrium problem with contact: both ends
// of every fibre held, the contact elements of one detection installed with a zone penalty of 400 (every
// element pressing). Shared by bench_contact_newton and bench_mpi_solve.

#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "nodus/contact/contact_term.hpp"
#include "nodus/contact/detection.hpp"
#include "nodus/loading/boundary_conditions.hpp"
#include "nodus/simulation/equilibrium_problem.hpp"
#include "twisted_bundle.hpp"

namespace nodus::bench {

/// The bundle of the contact benchmarks: `fibres` fibres of 100 elements, 10 mm long, R = 0.1 mm, on a
/// lattice of 1.99 R (neighbours overlap by 0.01 R).
inline Bundle contact_bundle(int fibres) {
  return twisted_bundle(fibres, 100, 10.0, 0.1, 1.99);
}

/// The nodes held in it: both ends of every fibre.
inline std::vector<int> held_nodes(const model::Model& model) {
  std::vector<int> nodes;
  for (const beam::Beam& beam : model.beams()) {
    nodes.push_back(beam.node(0));
    nodes.push_back(beam.node(beam.num_nodes() - 1));
  }
  return nodes;
}

/// The nodes each contact element of `geometry` couples (ContactTerm::couplings), in the elements' order.
inline std::vector<std::vector<int>> contact_couplings(const model::Model& model,
                                                       const contact::ContactGeometry& geometry) {
  contact::ContactTerm term(model);
  term.set_elements(geometry, std::vector<double>(geometry.zones.size(), 400.0),
                    std::vector<Eigen::Vector3d>(geometry.elements.size(), Eigen::Vector3d::Zero()));
  std::vector<std::vector<int>> groups;
  term.couplings(groups);
  return groups;
}

struct Setup {
  bench::Bundle bundle;
  loading::Conditions conditions;
  std::unique_ptr<simulation::EquilibriumProblem> problem;
  contact::ContactGeometry geometry;

  explicit Setup(int fibres) : bundle(contact_bundle(fibres)) {
    const model::Model& model = bundle.model;
    const loading::DofMask all{true, true, true, true, true, true, true, true, true};
    for (int node : held_nodes(model))
      conditions.activate(conditions.add_motion("end", node, all), 0.0, bundle.x);
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
