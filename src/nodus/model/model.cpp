#include "nodus/model/model.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>

#include "nodus/solver/sparse_assembler.hpp"

namespace nodus::model {

int Model::add_beam(const beam::BeamDefinition& definition) {
  if (dofs_.num_blocks() != num_nodes_)
    throw std::logic_error("Model::add_beam: beams come before any other unknowns");
  beams_.emplace_back(definition, num_nodes_);
  const beam::Beam& b = beams_.back();
  properties_.push_back(b.element_properties(gauss_points_));
  properties_.back().fold_stiffness = fold_stiffness_;
  properties_.back().fold_barrier = fold_barrier_;
  const int index = static_cast<int>(beams_.size()) - 1;
  first_element_.push_back(num_elements());
  for (int e = 0; e < b.num_elements(); ++e) elements_.push_back({index, b.node(2 * e)});
  for (int i = 0; i < b.num_nodes(); ++i) dofs_.add_block(kBeamNodeKinds);
  reference_.conservativeResize(dofs_.num_dofs());
  for (int i = 0; i < b.num_nodes(); ++i)
    reference_.segment<beam::kNodeDofs>(node_dof(b.node(i))) = b.reference_node(i);
  num_nodes_ += b.num_nodes();
  return index;
}

int Model::add_unknowns(std::span<const DofKind> kinds, const Eigen::VectorXd& initial) {
  if (initial.size() != static_cast<Eigen::Index>(kinds.size()))
    throw std::invalid_argument("Model::add_unknowns: one initial value per unknown");
  const int block = dofs_.add_block(kinds);
  reference_.conservativeResize(dofs_.num_dofs());
  reference_.tail(initial.size()) = initial;
  return block;
}

int Model::add_body(std::string name, std::vector<int> nodes) {
  if (nodes.empty()) throw std::invalid_argument("Model::add_body: body '" + name + "' binds no section");
  std::vector<int> sorted = nodes;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
    throw std::invalid_argument("Model::add_body: body '" + name + "' binds a section twice");
  RigidBody body;
  body.name = std::move(name);
  for (int node : nodes) {
    if (node < 0 || node >= num_nodes_) throw std::out_of_range("Model::add_body: no such node");
    body.reference_point += reference_.segment<3>(node_dof(node));
  }
  body.reference_point /= static_cast<double>(nodes.size());
  body.nodes = std::move(nodes);
  Eigen::VectorXd initial = Eigen::VectorXd::Zero(6);
  initial.head<3>() = body.reference_point;
  body.block = add_unknowns(kBodyKinds, initial);
  bodies_.push_back(std::move(body));
  return static_cast<int>(bodies_.size()) - 1;
}

int Model::node_beam(int node) const {
  const auto it = std::upper_bound(beams_.begin(), beams_.end(), node,
                                   [](int n, const beam::Beam& b) { return n < b.first_node(); });
  if (it == beams_.begin() || node >= num_nodes_) throw std::out_of_range("Model::node_beam: no such node");
  return static_cast<int>(it - beams_.begin()) - 1;
}

std::vector<std::vector<int>> Model::element_nodes() const {
  std::vector<std::vector<int>> nodes;
  nodes.reserve(elements_.size());
  for (const Element& e : elements_) nodes.push_back({e.first_node, e.first_node + 1, e.first_node + 2});
  return nodes;
}

FoldCheck Model::fold_check(const Eigen::VectorXd& x) const {
  FoldCheck check;
  for (int e = 0; e < num_elements(); ++e) {
    const beam::ElementVector x_e = gather(x, e);
    const beam::ElementProperties& p = properties_[static_cast<std::size_t>(elements_[e].beam)];
    const auto look = [&](double xi) {
      const double j = beam::orientation(beam::element_kinematics(x_e, p.length, xi));
      if (check.orientation_element < 0 || j < check.min_orientation) {
        check.min_orientation = j;
        check.orientation_element = e;
      }
    };
    for (const beam::GaussPoint& gp : beam::gauss_rule(p.gauss_points)) look(gp.xi);
    look(0.0);
    const double chord = (x_e.segment<3>(2 * beam::kNodeDofs) - x_e.segment<3>(0)).norm() / p.length;
    if (check.chord_element < 0 || chord < check.min_chord) {
      check.min_chord = chord;
      check.chord_element = e;
    }
  }
  return check;
}

beam::ElementVector Model::gather(const Eigen::VectorXd& x, int element) const {
  return x.segment<beam::kElementDofs>(node_dof(elements_[static_cast<std::size_t>(element)].first_node));
}

Eigen::Matrix<double, beam::kNumStrains, Eigen::Dynamic> Model::node_strains(const Eigen::VectorXd& x) const {
  Eigen::Matrix<double, beam::kNumStrains, Eigen::Dynamic> strains =
      Eigen::Matrix<double, beam::kNumStrains, Eigen::Dynamic>::Zero(beam::kNumStrains, num_nodes_);
  Eigen::VectorXi count = Eigen::VectorXi::Zero(num_nodes_);
  for (int e = 0; e < num_elements(); ++e) {
    const Element& el = elements_[static_cast<std::size_t>(e)];
    const beam::ElementVector x_e = gather(x, e);
    const double h = properties_[static_cast<std::size_t>(el.beam)].length;
    for (int i = 0; i < 3; ++i) {
      strains.col(el.first_node + i) += beam::strain_measures(beam::element_kinematics(x_e, h, i - 1.0));
      ++count[el.first_node + i];
    }
  }
  for (int n = 0; n < num_nodes_; ++n) strains.col(n) /= count[n];
  return strains;
}

Eigen::Matrix<double, beam::kNumStrains, Eigen::Dynamic> Model::element_strains(const Eigen::VectorXd& x,
                                                                                double xi) const {
  Eigen::Matrix<double, beam::kNumStrains, Eigen::Dynamic> strains(beam::kNumStrains, num_elements());
  for (int e = 0; e < num_elements(); ++e) {
    const double h =
        properties_[static_cast<std::size_t>(elements_[static_cast<std::size_t>(e)].beam)].length;
    strains.col(e) = beam::strain_measures(beam::element_kinematics(gather(x, e), h, xi));
  }
  return strains;
}

double Model::internal_energy(const Eigen::VectorXd& x) const {
  double energy = 0.0;
  for (int e = 0; e < num_elements(); ++e)
    energy += beam::element_energy(gather(x, e), properties_[static_cast<std::size_t>(elements_[e].beam)]);
  return energy;
}

void Model::internal_force(const Eigen::VectorXd& x, Eigen::VectorXd& force,
                           solver::SparseAssembler* assembler) const {
  force.setZero(num_dofs());
  if (assembler) assembler->set_zero();
  InternalForceAssembly assembly;
  add_internal_force(x, force, assembler, assembly);
}

void Model::add_internal_force(const Eigen::VectorXd& x, Eigen::VectorXd& force,
                               solver::SparseAssembler* assembler, InternalForceAssembly& assembly,
                               solver::BlockRange blocks) const {
  // The elements with a node among `blocks` (all of them, unless the run is distributed), in order.
  std::vector<int> some;
  const bool all = blocks.first <= 0 && blocks.last >= num_nodes();
  if (!all)
    for (int e = 0; e < num_elements(); ++e) {
      const int n = elements_[static_cast<std::size_t>(e)].first_node;
      if (blocks.contains(n) || blocks.contains(n + 1) || blocks.contains(n + 2)) some.push_back(e);
    }
  const auto element = [&](std::size_t k) { return all ? k : static_cast<std::size_t>(some[k]); };
  const auto compute = [&](std::size_t k, ElementForces& out) {
    const std::size_t e = element(k);
    beam::element_internal_force(gather(x, static_cast<int>(e)),
                                 properties_[static_cast<std::size_t>(elements_[e].beam)], out.force,
                                 assembler ? &out.tangent : nullptr);
  };
  // Each thread adds the entries of its own nodes (blocks), so the sums do not depend on the thread count.
  const auto scatter = [&](std::size_t k, const ElementForces& in, solver::BlockRange nodes_added) {
    const int first_node = elements_[element(k)].first_node;
    for (int a = 0; a < 3; ++a)
      if (nodes_added.contains(first_node + a))
        force.segment<beam::kNodeDofs>(node_dof(first_node + a)) +=
            in.force.segment<beam::kNodeDofs>(beam::kNodeDofs * a);
    if (assembler) {
      const std::array<int, 3> nodes{first_node, first_node + 1, first_node + 2};
      assembler->add(nodes, in.tangent, nodes_added);
    }
  };
  const auto split = [&](int parts) {
    return assembler ? assembler->split_columns(parts) : solver::even_split(dofs_.num_blocks(), parts);
  };
  // The force alone costs about 0.5 us per element, 1/20 of the force and tangent (docs/performance.md).
  assembly.run(all ? elements_.size() : some.size(), compute, scatter, split, assembler ? 1.0 : 0.05);
}

}  // namespace nodus::model
