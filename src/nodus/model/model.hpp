#pragma once
/// The mechanical model: the beams of an assembly, their nodes and unknowns, and their internal virtual work
/// [Durville 2012, Eq. 3 and 8]. Its unknowns are handed out by a DofMap: the beams' nodes first, each a
/// block of its current values (r, g1, g2), nine per node, node by node (node n is block n); then whatever
/// other unknowns were added (add_unknowns). The displacement is the difference to `reference()`.

#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "nodus/beam/beam.hpp"
#include "nodus/beam/shape_functions.hpp"
#include "nodus/model/dof_map.hpp"
#include "nodus/solver/ordered_assembly.hpp"

namespace nodus::solver {
class SparseAssembler;
}

namespace nodus::model {

/// One beam element's internal forces and their tangent, as computed before they are added up.
struct ElementForces {
  beam::ElementVector force;
  beam::ElementMatrix tangent;
};
/// The buffers of the internal forces' assembly on all threads, kept across calls.
using InternalForceAssembly = solver::OrderedAssembly<ElementForces>;

/// What the nine unknowns of a beam node measure: r, then g1 and g2.
inline constexpr DofKind kBeamNodeKinds[beam::kNodeDofs] = {
    DofKind::position, DofKind::position, DofKind::position, DofKind::director, DofKind::director,
    DofKind::director, DofKind::director, DofKind::director, DofKind::director};

/// What the six unknowns of a rigid body measure: its reference point c, then its rotation vector theta.
inline constexpr DofKind kBodyKinds[6] = {DofKind::position, DofKind::position, DofKind::position,
                                          DofKind::rotation, DofKind::rotation, DofKind::rotation};

/// A rigid body: six unknowns (c, theta), bound to beam sections by averaged conditions
/// (model/averaged_conditions_term.hpp). Its rotation is Q(theta) (model/rotation_vector.hpp).
struct RigidBody {
  std::string name;
  int block = 0;                                              ///< its block of unknowns in dofs()
  std::vector<int> nodes;                                     ///< the global nodes of the bound sections
  Eigen::Vector3d reference_point = Eigen::Vector3d::Zero();  ///< c in the reference state: the mean of the
                                                              ///< bound section centres [mm]
};

/// Whether any element is folded back on itself (Model::fold_check).
struct FoldCheck {
  /// The smallest orientation det[g1, g2, r'] (beam::orientation) over every Gauss point and element centre
  /// [-]: 1 at rest, <= 0 where an axis runs against its section.
  double min_orientation = 1.0;
  int orientation_element = -1;  ///< the element where it is found (-1: no elements)
  /// The smallest chord |r_3 - r_1| / h of an element (its end nodes' distance over its reference length)
  /// [-]: 1 for a straight unstretched element, 1 - (h/R)^2/24 + O((h/R)^4) on an unstretched arc of radius
  /// R, 0 for a complete fold.
  double min_chord = 1.0;
  int chord_element = -1;  ///< the element where it is found
};

class Model {
 public:
  /// `fold_stiffness`, `fold_barrier`: beta of beam::fold_energy and gamma of
  /// beam::orientation_barrier_energy, for every element.
  explicit Model(int gauss_points = 2, double fold_stiffness = 0.0, double fold_barrier = 1.0)
      : gauss_points_(gauss_points), fold_stiffness_(fold_stiffness), fold_barrier_(fold_barrier) {
    // Checked here: the elements are evaluated in parallel regions, which an exception must not leave.
    static_cast<void>(beam::gauss_rule(gauss_points));
  }

  /// Adds a beam, its nodes a block of nine unknowns each; returns its index. Beams come before any other
  /// unknowns (std::logic_error otherwise), so that node n is block n.
  int add_beam(const beam::BeamDefinition& definition);
  /// Adds a block of unknowns of the given kinds, starting at `initial` in the reference state; returns the
  /// block's index in dofs().
  int add_unknowns(std::span<const DofKind> kinds, const Eigen::VectorXd& initial);

  /// Adds a rigid body bound to the sections of global nodes `nodes` (at least one, none twice): a block of
  /// six unknowns (kBodyKinds) starting at c = the mean of their reference centres and theta = 0; returns its
  /// index in bodies(). After the beams.
  int add_body(std::string name, std::vector<int> nodes);
  const std::vector<RigidBody>& bodies() const { return bodies_; }
  const RigidBody& body(int i) const { return bodies_.at(static_cast<std::size_t>(i)); }
  /// The first of the six unknowns of body `i`.
  int body_dof(int i) const { return dofs_.first(body(i).block); }
  /// The beam that global node `node` belongs to.
  int node_beam(int node) const;

  const std::vector<beam::Beam>& beams() const { return beams_; }
  const beam::Beam& beam(int i) const { return beams_.at(static_cast<std::size_t>(i)); }
  int num_nodes() const { return num_nodes_; }
  int num_dofs() const { return dofs_.num_dofs(); }
  /// The blocks of unknowns.
  const DofMap& dofs() const { return dofs_; }
  /// The first unknown of beam node `node`.
  int node_dof(int node) const { return dofs_.first(node); }
  int num_elements() const { return static_cast<int>(elements_.size()); }
  /// Global index of the first element of beam `b` (elements are numbered beam after beam).
  int first_element(int b) const { return first_element_[static_cast<std::size_t>(b)]; }
  /// The beam of global element `element`.
  int element_beam(int element) const { return elements_[static_cast<std::size_t>(element)].beam; }
  int gauss_points() const { return gauss_points_; }
  double fold_stiffness() const { return fold_stiffness_; }
  double fold_barrier() const { return fold_barrier_; }

  /// Reference configuration (every unknown: nine values per node, then the other blocks).
  const Eigen::VectorXd& reference() const { return reference_; }
  /// Global node indices of each element (three per element).
  std::vector<std::vector<int>> element_nodes() const;
  /// The first of the three consecutive global nodes of `element`.
  int element_first_node(int element) const {
    return elements_[static_cast<std::size_t>(element)].first_node;
  }
  /// The 27 element unknowns gathered from the global vector.
  beam::ElementVector gather(const Eigen::VectorXd& x, int element) const;

  /// The 15 strain measures (beam/strain_measures.hpp) at every node, one column per node; at a node shared
  /// by two elements, the mean of the two elements' values.
  Eigen::Matrix<double, beam::kNumStrains, Eigen::Dynamic> node_strains(const Eigen::VectorXd& x) const;

  /// The 15 strain measures of every element at its local coordinate `xi` in [-1, 1] (0: the element centre),
  /// one column per element.
  Eigen::Matrix<double, beam::kNumStrains, Eigen::Dynamic> element_strains(const Eigen::VectorXd& x,
                                                                           double xi = 0.0) const;

  /// The orientation at every Gauss point and element centre and the chord of every element in state `x`.
  FoldCheck fold_check(const Eigen::VectorXd& x) const;

  /// Total strain energy [N mm].
  double internal_energy(const Eigen::VectorXd& x) const;
  /// Internal force vector over all unknowns (prescribed ones too: there it carries the reactions), and the
  /// tangent over the free unknowns into `assembler` if not null.
  void internal_force(const Eigen::VectorXd& x, Eigen::VectorXd& force,
                      solver::SparseAssembler* assembler) const;
  /// Adds the internal forces to `force` (num_dofs() values) and, if `assembler` is not null, their tangent.
  /// The elements are evaluated on all threads, and added up in element order (`assembly` holds the
  /// buffers): the sums do not depend on the number of threads. Only the elements with a node among
  /// `blocks` are evaluated (a rank of a distributed run: its rows are then those of one process).
  void add_internal_force(const Eigen::VectorXd& x, Eigen::VectorXd& force,
                          solver::SparseAssembler* assembler, InternalForceAssembly& assembly,
                          solver::BlockRange blocks = {}) const;

 private:
  struct Element {
    int beam;
    int first_node;  ///< nodes first_node, first_node + 1, first_node + 2
  };

  int gauss_points_;
  double fold_stiffness_;
  double fold_barrier_;
  std::vector<beam::Beam> beams_;
  std::vector<RigidBody> bodies_;
  std::vector<beam::ElementProperties> properties_;  ///< one per beam
  std::vector<Element> elements_;
  std::vector<int> first_element_;  ///< per beam: global index of its first element
  Eigen::VectorXd reference_;
  DofMap dofs_;
  int num_nodes_ = 0;
};

}  // namespace nodus::model
