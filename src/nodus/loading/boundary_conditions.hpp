#pragma once
/// Boundary conditions on cross-sections: prescribed motions (clamps are motions that stay put) and loads
/// (a dead force on the centre, a moment about a fixed axis) [Durville 2012, Eq. 4]. A prescribed rotation
/// acts by rotating the section directors: g_a(t) = Q(t) g_a(activation), and the centre about a pivot p
/// fixed at activation: r(t) = p + u(t) + Q(t) (r(activation) - p); without a pivot p is the centre itself.
/// A rigid condition moves every node of a list (a tool beam) that way. A bind holds the translations of
/// several rigid bodies together by a penalty (docs/bodies.md, "Bodies bound together").

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "nodus/beam/beam_element.hpp"
#include "nodus/loading/moment_load.hpp"
#include "nodus/loading/path.hpp"

namespace nodus::solver {
class SparseAssembler;
}

namespace nodus::loading {

/// Which of a beam node's nine unknowns (r, g1, g2) a condition prescribes; for a rigid body, the first six
/// entries: its point c, then its rotation vector theta.
using DofMask = std::array<bool, beam::kNodeDofs>;

/// A rigid body as a condition sees it: its block of six unknowns (c, theta) and the first of them.
struct BodyRef {
  int block = 0;
  int dof = 0;
};
using NodeVector = Eigen::Matrix<double, beam::kNodeDofs, 1>;

/// Force and moment that the supports (or loads) exert on a section [N, N mm], moment about its centre.
struct SectionForce {
  Vec3 force = Vec3::Zero();
  Vec3 moment = Vec3::Zero();
};

enum class ConditionKind { motion, load, bind };

/// What a condition carries through a run besides what it was built with (name, kind, nodes, dofs, given
/// pivot): whether it acts, its anchors and pivot taken at activation, its paths (motion keyframes, load
/// values, the ramp of a released support) and the fixed axis and turn count of its moment. Saving it and
/// restoring it into a Conditions built the same way continues the run exactly.
struct ConditionState {
  bool active = false;
  /// Per node (its nine unknowns) or body (c, theta and, for a load, the body-frame vector whose angle the
  /// moment turns), at activation.
  std::vector<NodeVector> anchors;
  Vec3 pivot = Vec3::Zero();  ///< at activation [mm]
  Path<Vec3> translation{Vec3::Zero()};
  Path<Vec3> rotation{Vec3::Zero()};  ///< rotation vector [rad]
  Path<Vec3> force{Vec3::Zero()};
  Path<NodeVector> director_force{NodeVector::Zero()};
  Path<double> moment{0.0};
  Vec3 axis = Vec3::UnitZ();
  int director = 0;
  std::optional<AxisAngle::State> angle;
};

class Conditions {
 public:
  /// A prescribed motion of the dofs in `mask` of global node `node`; a clamp is a motion with no keyframes.
  /// `pivot` [mm]: the fixed point the rotation turns the centre about (none: the centre itself).
  int add_motion(std::string name, int node, const DofMask& mask, std::optional<Vec3> pivot = std::nullopt);
  /// A rigid motion of all nine unknowns of every node in `nodes` (a tool beam): rotation about `pivot`
  /// (none: the centre of the middle node at activation). It cannot be released.
  int add_rigid(std::string name, std::vector<int> nodes, std::optional<Vec3> pivot = std::nullopt);
  /// A load on global node `node`: force [N] and moment [N mm] at load time 0. The moment's axis is fixed:
  /// `moment_axis` (unit) for the whole run; its value is moment_axis * moment.
  int add_load(std::string name, int node, const Vec3& force, const Vec3& moment_axis, double moment);
  /// A prescribed motion of the unknowns in `mask` (first six entries: c, theta) of one or more rigid bodies:
  /// c(t) = p + u(t) + Q(t) (c(activation) - p), Q_body(t) = Q(t) Q_body(activation); `pivot` p [mm] (none:
  /// the mean of the bodies' points c at activation). A clamp is a motion with no keyframes.
  int add_body_motion(std::string name, std::vector<BodyRef> bodies, const DofMask& mask,
                      std::optional<Vec3> pivot = std::nullopt);
  /// A load on a rigid body: a dead force [N] on its point c and a moment [N mm] about the fixed axis
  /// `moment_axis`, whose work is the moment times the body's angle about that axis (AxisAngle of a
  /// body-fixed vector normal to it), so that it is conservative.
  int add_body_load(std::string name, BodyRef body, const Vec3& force, const Vec3& moment_axis,
                    double moment);
  /// Binds the translations `mask` (entries 0-2: x, y, z of the points c) of two or more rigid bodies: from
  /// activation on, their displacements u_i = c_i - c_i(activation) are held equal in those directions by
  /// the penalty energy (k / 2) sum_i |P (u_i - u_mean)|^2, k [N/mm]. Nothing else of the bodies is held,
  /// and the forces it exerts sum to zero. It is never released.
  int add_body_bind(std::string name, std::vector<BodyRef> bodies, const DofMask& mask, double stiffness);
  /// Sets the penalty stiffness k [N/mm] of a bind.
  void set_bind_stiffness(int c, double stiffness);
  double bind_stiffness(int c) const { return at(c).stiffness; }

  int size() const { return static_cast<int>(items_.size()); }
  const std::string& name(int c) const { return at(c).name; }
  ConditionKind kind(int c) const { return at(c).kind; }
  /// The DofMap blocks of every node or body condition c acts on.
  const std::vector<int>& blocks(int c) const { return at(c).blocks; }
  /// The node of a motion or load; the first node of a rigid condition (beam sections only).
  int node(int c) const { return at(c).nodes.front(); }
  /// Whether condition c acts on rigid bodies rather than beam sections.
  bool on_bodies(int c) const { return at(c).body; }
  /// The DofMap block of the (first) node or body condition c acts on.
  int block(int c) const { return at(c).blocks.front(); }
  bool active(int c) const { return at(c).active; }
  /// The fixed axis of the moment of a load (unit); for a released motion, that of its ramped-down moment.
  const Vec3& moment_axis(int c) const { return at(c).axis; }

  /// The state of condition c (see ConditionState).
  ConditionState state(int c) const;
  /// Restores the state of condition c, as state(c) returned it in a Conditions built the same way.
  void restore(int c, const ConditionState& state);

  /// Switches condition c on at load time `time`; a motion is anchored at the current state of its section.
  void activate(int c, double time, const Eigen::VectorXd& x);
  /// Switches condition c off. A motion's support is not removed at once: it is replaced by the load it
  /// exerts at `time` (`residual`: the out-of-balance forces f_int - f_ext over all unknowns, at its
  /// unknowns the reactions), which then decreases linearly to zero at `end_time`, so that the release is
  /// quasi-static and controlled by the stage's steps. That load is dead: a force on the centre and forces on
  /// the directors (whose moment is the support's moment at `time`), or on a body's rotation vector. A load
  /// simply stops.
  void release(int c, double time, const Eigen::VectorXd& residual, double end_time);

  /// Adds a keyframe of a motion: translation [mm] and rotation vector [rad], cumulative since activation.
  void add_motion_keyframe(int c, double time, const Vec3& translation, const Vec3& rotation);
  /// Adds a keyframe of a load: force [N], moment about the fixed axis [N mm].
  void add_load_keyframe(int c, double time, const Vec3& force, double moment);
  /// Holds every path at its current value up to `time` (call at the start of a stage, before keyframes).
  void hold_until(double time);

  /// Mask of the prescribed unknowns (all nodes). Throws std::runtime_error naming both conditions if two
  /// active conditions prescribe the same unknown.
  std::vector<bool> prescribed(int num_dofs) const;
  /// Sets the prescribed unknowns of x to their values at load time t.
  void apply_prescribed(double time, Eigen::VectorXd& x) const;
  /// Generalised external forces of the active loads at time t and state x.
  void external_force(double time, const Eigen::VectorXd& x, Eigen::VectorXd& f_ext) const;
  /// Adds minus the derivative of the external forces (load stiffness of moments, the binds' penalty) to the
  /// tangent.
  void add_load_tangent(double time, const Eigen::VectorXd& x, solver::SparseAssembler& assembler) const;
  /// Accepts the state x as converged (moment angles count their turns).
  void commit(const Eigen::VectorXd& x);

  /// The force and moment of condition c on its section: for a motion, the reaction of the support, read from
  /// the out-of-balance forces `residual` = f_int - f_ext at the section's unknowns; for a load, the load.
  /// For a rigid condition: the resultant on all its nodes, moment about the moved pivot p + u(t). For
  /// bodies: the resultant on the bodies, moment about the moved pivot (one body: its point c). For a bind:
  /// the force it exerts on its first body (those on the others sum to minus it), no moment.
  SectionForce section_force(int c, double time, const Eigen::VectorXd& x,
                             const Eigen::VectorXd& residual) const;

 private:
  struct Item {
    std::string name;
    ConditionKind kind = ConditionKind::motion;
    std::vector<int> nodes;   ///< one node, or all the nodes of a rigid condition; empty for bodies
    std::vector<int> blocks;  ///< per target (node or body): its DofMap block
    std::vector<int> first;   ///< per target: its first unknown
    DofMask mask{};
    bool active = false;
    bool rigid = false;
    bool body = false;  ///< the targets are rigid bodies (six unknowns: c, theta)
    // motion
    std::vector<NodeVector> anchors;  ///< per node, at activation
    std::optional<Vec3> given_pivot;
    Vec3 pivot = Vec3::Zero();  ///< at activation
    Path<Vec3> translation{Vec3::Zero()};
    Path<Vec3> rotation{Vec3::Zero()};
    // load, or a released motion's support being ramped down
    Path<Vec3> force{Vec3::Zero()};
    Path<NodeVector> director_force{
        NodeVector::Zero()};  ///< dead generalised forces (released supports only)
    Path<double> moment{0.0};
    Vec3 axis = Vec3::UnitZ();
    int director = 0;  ///< 0: g1, 1: g2, the one the moment acts through
    std::optional<AxisAngle> angle;
    // bind
    double stiffness = 0.0;  ///< k [N/mm]
  };
  const Item& at(int c) const { return items_.at(static_cast<std::size_t>(c)); }
  Item& at(int c) { return items_.at(static_cast<std::size_t>(c)); }
  NodeVector prescribed_values(const Item& item, std::size_t k, double time) const;
  /// The number of unknowns of each target: 9 (node) or 6 (body).
  static int width(const Item& item) { return item.body ? 6 : beam::kNodeDofs; }
  /// The moment [N mm] about a body's point of the generalised forces `f_theta` on its rotation vector.
  static Vec3 body_moment(const Vec3& theta, const Vec3& f_theta);
  static void anchor_moment(Item& item, const NodeVector& state);
  /// The forces f_i = -k P (u_i - u_mean) [N] a bind exerts on the points of its bodies.
  static std::vector<Vec3> bind_forces(const Item& item, const Eigen::VectorXd& x);
  /// Whether the item's force and moment act: an active load, or a released motion.
  static bool applies_load(const Item& item);

  std::vector<Item> items_;
};

}  // namespace nodus::loading
