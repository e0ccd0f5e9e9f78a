#include "nodus/loading/boundary_conditions.hpp"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include "nodus/solver/sparse_assembler.hpp"

namespace nodus::loading {
namespace {

Eigen::Matrix3d rotation_matrix(const Vec3& rotation_vector) {
  const double angle = rotation_vector.norm();
  if (angle == 0.0) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, rotation_vector / angle).toRotationMatrix();
}

}  // namespace

int Conditions::add_motion(std::string name, int node, const DofMask& mask, std::optional<Vec3> pivot) {
  Item item;
  item.name = std::move(name);
  item.kind = ConditionKind::motion;
  item.nodes = {node};
  item.mask = mask;
  item.given_pivot = pivot;
  items_.push_back(std::move(item));
  return size() - 1;
}

int Conditions::add_rigid(std::string name, std::vector<int> nodes, std::optional<Vec3> pivot) {
  if (nodes.empty()) throw std::invalid_argument("add_rigid: no nodes");
  Item item;
  item.name = std::move(name);
  item.kind = ConditionKind::motion;
  item.rigid = true;
  item.nodes = std::move(nodes);
  item.mask.fill(true);
  item.given_pivot = pivot;
  items_.push_back(std::move(item));
  return size() - 1;
}

int Conditions::add_load(std::string name, int node, const Vec3& force, const Vec3& moment_axis,
                         double moment) {
  Item item;
  item.name = std::move(name);
  item.kind = ConditionKind::load;
  item.nodes = {node};
  item.force.reset(0.0, force);
  item.moment.reset(0.0, moment);
  item.axis = moment_axis.normalized();
  items_.push_back(std::move(item));
  return size() - 1;
}

ConditionState Conditions::state(int c) const {
  const Item& item = at(c);
  ConditionState out;
  out.active = item.active;
  out.anchors = item.anchors;
  out.pivot = item.pivot;
  out.translation = item.translation;
  out.rotation = item.rotation;
  out.force = item.force;
  out.director_force = item.director_force;
  out.moment = item.moment;
  out.axis = item.axis;
  out.director = item.director;
  if (item.angle) out.angle = item.angle->state();
  return out;
}

void Conditions::restore(int c, const ConditionState& state) {
  Item& item = at(c);
  if (!state.anchors.empty() && state.anchors.size() != item.nodes.size())
    throw std::invalid_argument(fmt::format("condition '{}': {} anchors restored for {} nodes", item.name,
                                            state.anchors.size(), item.nodes.size()));
  item.active = state.active;
  item.anchors = state.anchors;
  item.pivot = state.pivot;
  item.translation = state.translation;
  item.rotation = state.rotation;
  item.force = state.force;
  item.director_force = state.director_force;
  item.moment = state.moment;
  item.axis = state.axis;
  item.director = state.director;
  item.angle.reset();
  if (state.angle) item.angle.emplace(*state.angle);
}

void Conditions::anchor_moment(Item& item, const NodeVector& state) {
  // The moment acts through the director most nearly normal to its axis.
  const Vec3 g1 = state.segment<3>(3), g2 = state.segment<3>(6);
  item.director =
      std::abs(g1.normalized().dot(item.axis)) <= std::abs(g2.normalized().dot(item.axis)) ? 0 : 1;
  item.angle.emplace(item.axis, item.director == 0 ? g1 : g2);
}

void Conditions::activate(int c, double time, const Eigen::VectorXd& x) {
  Item& item = at(c);
  item.active = true;
  const NodeVector state = x.segment<beam::kNodeDofs>(beam::kNodeDofs * item.nodes.front());
  if (item.kind == ConditionKind::motion) {
    item.anchors.clear();
    for (int node : item.nodes) item.anchors.push_back(x.segment<beam::kNodeDofs>(beam::kNodeDofs * node));
    item.pivot =
        item.given_pivot ? *item.given_pivot : item.anchors[item.anchors.size() / 2].head<3>().eval();
    item.translation.reset(time, Vec3::Zero());
    item.rotation.reset(time, Vec3::Zero());
    item.force.reset(time, Vec3::Zero());
    item.moment.reset(time, 0.0);
    item.director_force.reset(time, NodeVector::Zero());
  } else {
    anchor_moment(item, state);
  }
}

void Conditions::release(int c, double time, const NodeVector& reaction, double end_time) {
  Item& item = at(c);
  if (item.rigid) throw std::logic_error("release of the rigid condition '" + item.name + "'");
  if (item.active && item.kind == ConditionKind::motion) {
    // The support's generalised force on the unknowns it held (the force on the centre, and on the
    // directors the forces whose moment is the support's moment) acts on as a dead load that decreases to
    // zero. A moment about a fixed axis (as a moment load acts) is not used here: its angle is measured with
    // one director, and a freed section that turns that director towards the axis (a knot's tail) makes it
    // singular; the stiffness m H of the vanishing moment then disappears abruptly at the end of the ramp.
    NodeVector f = NodeVector::Zero();
    for (int d = 0; d < beam::kNodeDofs; ++d)
      if (item.mask[static_cast<std::size_t>(d)]) f[d] = reaction[d];
    NodeVector rest = f;
    rest.segment<3>(0).setZero();
    item.force.reset(time, f.segment<3>(0));
    item.force.add(end_time, Vec3::Zero());
    item.moment.reset(time, 0.0);
    item.director_force.reset(time, rest);
    item.director_force.add(end_time, NodeVector::Zero());
  }
  item.active = false;
}

void Conditions::hold_until(double time) {
  for (Item& item : items_) {
    if (item.translation.last_time() < time) item.translation.add(time, item.translation.at(time));
    if (item.rotation.last_time() < time) item.rotation.add(time, item.rotation.at(time));
    if (item.force.last_time() < time) item.force.add(time, item.force.at(time));
    if (item.moment.last_time() < time) item.moment.add(time, item.moment.at(time));
    if (item.director_force.last_time() < time) item.director_force.add(time, item.director_force.at(time));
  }
}

void Conditions::add_motion_keyframe(int c, double time, const Vec3& translation, const Vec3& rotation) {
  Item& item = at(c);
  if (item.kind != ConditionKind::motion) throw std::logic_error("add_motion_keyframe on a load");
  item.translation.add(time, translation);
  item.rotation.add(time, rotation);
}

void Conditions::add_load_keyframe(int c, double time, const Vec3& force, double moment) {
  Item& item = at(c);
  if (item.kind != ConditionKind::load) throw std::logic_error("add_load_keyframe on a motion");
  item.force.add(time, force);
  item.moment.add(time, moment);
}

std::vector<bool> Conditions::prescribed(int num_dofs) const {
  std::vector<bool> mask(static_cast<std::size_t>(num_dofs), false);
  std::vector<int> owner(static_cast<std::size_t>(num_dofs), -1);
  for (int c = 0; c < size(); ++c) {
    const Item& item = at(c);
    if (!item.active || item.kind != ConditionKind::motion) continue;
    for (int node : item.nodes)
      for (int d = 0; d < beam::kNodeDofs; ++d) {
        if (!item.mask[d]) continue;
        const auto dof = static_cast<std::size_t>(beam::kNodeDofs * node + d);
        if (owner[dof] >= 0)
          throw std::runtime_error(
              fmt::format("conditions '{}' and '{}' both prescribe unknown {} of node {}",
                          at(owner[dof]).name, item.name, d, node));
        owner[dof] = c;
        mask[dof] = true;
      }
  }
  return mask;
}

NodeVector Conditions::prescribed_values(const Item& item, std::size_t k, double time) const {
  const Eigen::Matrix3d q = rotation_matrix(item.rotation.at(time));
  const NodeVector& anchor = item.anchors[k];
  NodeVector v;
  v << item.pivot + item.translation.at(time) + q * (anchor.segment<3>(0) - item.pivot),
      q * anchor.segment<3>(3), q * anchor.segment<3>(6);
  return v;
}

void Conditions::apply_prescribed(double time, Eigen::VectorXd& x) const {
  for (const Item& item : items_) {
    if (!item.active || item.kind != ConditionKind::motion) continue;
    for (std::size_t k = 0; k < item.nodes.size(); ++k) {
      const NodeVector v = prescribed_values(item, k, time);
      for (int d = 0; d < beam::kNodeDofs; ++d)
        if (item.mask[d]) x[beam::kNodeDofs * item.nodes[k] + d] = v[d];
    }
  }
}

bool Conditions::applies_load(const Item& item) {
  if (item.rigid) return false;
  return item.kind == ConditionKind::load ? item.active : !item.active;  // a released support ramps down
}

void Conditions::external_force(double time, const Eigen::VectorXd& x, Eigen::VectorXd& f_ext) const {
  for (const Item& item : items_) {
    if (!applies_load(item)) continue;
    const int base = beam::kNodeDofs * item.nodes.front();
    f_ext.segment<3>(base) += item.force.at(time);
    f_ext.segment<beam::kNodeDofs>(base) += item.director_force.at(time);
    const double m = item.moment.at(time);
    if (m != 0.0) {
      const int v = base + 3 + 3 * item.director;
      f_ext.segment<3>(v) += m * item.angle->gradient(x.segment<3>(v));
    }
  }
}

void Conditions::add_load_tangent(double time, const Eigen::VectorXd& x,
                                  solver::SparseAssembler& assembler) const {
  for (const Item& item : items_) {
    if (!applies_load(item)) continue;
    const double m = item.moment.at(time);
    if (m == 0.0) continue;
    const int v = beam::kNodeDofs * item.nodes.front() + 3 + 3 * item.director;
    Eigen::Matrix<double, beam::kNodeDofs, beam::kNodeDofs> k =
        Eigen::Matrix<double, beam::kNodeDofs, beam::kNodeDofs>::Zero();
    k.block<3, 3>(3 + 3 * item.director, 3 + 3 * item.director) = -m * item.angle->hessian(x.segment<3>(v));
    const int nodes[1] = {item.nodes.front()};
    assembler.add(nodes, k);
  }
}

void Conditions::commit(const Eigen::VectorXd& x) {
  for (Item& item : items_)
    if (applies_load(item) && item.angle)
      item.angle->commit(x.segment<3>(beam::kNodeDofs * item.nodes.front() + 3 + 3 * item.director));
}

SectionForce Conditions::section_force(int c, double time, const Eigen::VectorXd& x,
                                       const Eigen::VectorXd& residual) const {
  const Item& item = at(c);
  const int base = beam::kNodeDofs * item.nodes.front();
  SectionForce out;
  if (applies_load(item)) {
    const NodeVector f = item.director_force.at(time);
    out.force = item.force.at(time) + f.segment<3>(0);
    out.moment = item.moment.at(time) * item.axis + x.segment<3>(base + 3).cross(f.segment<3>(3)) +
                 x.segment<3>(base + 6).cross(f.segment<3>(6));
    return out;
  }
  if (!item.active) return out;
  if (item.rigid) {  // resultant about the moved pivot
    const Vec3 centre = item.pivot + item.translation.at(time);
    for (int node : item.nodes) {
      const int b = beam::kNodeDofs * node;
      out.force += residual.segment<3>(b);
      out.moment += (x.segment<3>(b) - centre).cross(residual.segment<3>(b)) +
                    x.segment<3>(b + 3).cross(residual.segment<3>(b + 3)) +
                    x.segment<3>(b + 6).cross(residual.segment<3>(b + 6));
    }
    return out;
  }
  // f_int - f_ext at a prescribed section is what the support must supply; its moment about the centre is the
  // sum of g_a x (force on g_a).
  out.force = residual.segment<3>(base);
  out.moment = x.segment<3>(base + 3).cross(residual.segment<3>(base + 3)) +
               x.segment<3>(base + 6).cross(residual.segment<3>(base + 6));
  return out;
}

}  // namespace nodus::loading
