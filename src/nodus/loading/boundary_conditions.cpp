#include "nodus/loading/boundary_conditions.hpp"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include "nodus/model/rotation_vector.hpp"
#include "nodus/solver/sparse_assembler.hpp"

namespace nodus::loading {
namespace {

Eigen::Matrix3d rotation_matrix(const Vec3& rotation_vector) {
  const double angle = rotation_vector.norm();
  if (angle == 0.0) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, rotation_vector / angle).toRotationMatrix();
}

/// The targets of a condition on beam nodes: block n is node n, its unknowns 9 n .. 9 n + 8.
void node_targets(const std::vector<int>& nodes, std::vector<int>& blocks, std::vector<int>& first) {
  blocks = nodes;
  first.clear();
  for (int n : nodes) first.push_back(beam::kNodeDofs * n);
}

/// The targets of a condition on rigid bodies: each body's block and first unknown.
void body_targets(const std::vector<BodyRef>& bodies, std::vector<int>& blocks, std::vector<int>& first) {
  blocks.clear();
  first.clear();
  for (const BodyRef& b : bodies) {
    blocks.push_back(b.block);
    first.push_back(b.dof);
  }
}

}  // namespace

int Conditions::add_motion(std::string name, int node, const DofMask& mask, std::optional<Vec3> pivot) {
  Item item;
  item.name = std::move(name);
  item.kind = ConditionKind::motion;
  item.nodes = {node};
  node_targets(item.nodes, item.blocks, item.first);
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
  node_targets(item.nodes, item.blocks, item.first);
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
  node_targets(item.nodes, item.blocks, item.first);
  item.force.reset(0.0, force);
  item.moment.reset(0.0, moment);
  item.axis = moment_axis.normalized();
  items_.push_back(std::move(item));
  return size() - 1;
}

int Conditions::add_body_motion(std::string name, std::vector<BodyRef> bodies, const DofMask& mask,
                                std::optional<Vec3> pivot) {
  if (bodies.empty()) throw std::invalid_argument("add_body_motion: no bodies");
  Item item;
  item.name = std::move(name);
  item.kind = ConditionKind::motion;
  item.body = true;
  body_targets(bodies, item.blocks, item.first);
  item.mask = mask;
  for (int d = 6; d < beam::kNodeDofs; ++d) item.mask[static_cast<std::size_t>(d)] = false;
  item.given_pivot = pivot;
  items_.push_back(std::move(item));
  return size() - 1;
}

int Conditions::add_body_load(std::string name, BodyRef body, const Vec3& force, const Vec3& moment_axis,
                              double moment) {
  Item item;
  item.name = std::move(name);
  item.kind = ConditionKind::load;
  item.body = true;
  item.blocks = {body.block};
  item.first = {body.dof};
  item.force.reset(0.0, force);
  item.moment.reset(0.0, moment);
  item.axis = moment_axis.normalized();
  items_.push_back(std::move(item));
  return size() - 1;
}

int Conditions::add_body_bind(std::string name, std::vector<BodyRef> bodies, const DofMask& mask,
                              double stiffness) {
  if (bodies.size() < 2) throw std::invalid_argument("add_body_bind: fewer than two bodies");
  Item item;
  item.name = std::move(name);
  item.kind = ConditionKind::bind;
  item.body = true;
  body_targets(bodies, item.blocks, item.first);
  item.mask.fill(false);
  for (std::size_t d = 0; d < 3; ++d) item.mask[d] = mask[d];
  item.stiffness = stiffness;
  items_.push_back(std::move(item));
  return size() - 1;
}

void Conditions::set_bind_stiffness(int c, double stiffness) {
  Item& item = at(c);
  if (item.kind != ConditionKind::bind)
    throw std::logic_error("set_bind_stiffness on a condition not a bind");
  item.stiffness = stiffness;
}

std::vector<Vec3> Conditions::bind_forces(const Item& item, const Eigen::VectorXd& x) {
  const std::size_t n = item.first.size();
  std::vector<Vec3> u(n);
  Vec3 mean = Vec3::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    u[i] = x.segment<3>(item.first[i]) - item.anchors[i].head<3>();
    mean += u[i] / static_cast<double>(n);
  }
  for (std::size_t i = 0; i < n; ++i) {
    Vec3 f = -item.stiffness * (u[i] - mean);
    for (std::size_t d = 0; d < 3; ++d)
      if (!item.mask[d]) f[static_cast<int>(d)] = 0.0;
    u[i] = f;
  }
  return u;
}

Vec3 Conditions::body_moment(const Vec3& theta, const Vec3& f_theta) {
  // A variation d theta turns the body by the spin omega = T d theta, [T e_k]x = (dQ/dtheta_k) Q^T; the
  // work m . omega = f_theta . d theta gives f_theta = T^T m.
  const model::RotationDerivatives d = model::rotation_derivatives(theta, false);
  Eigen::Matrix3d t;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Matrix3d w = d.first[static_cast<std::size_t>(k)] * d.q.transpose();
    t.col(k) = Vec3(w(2, 1), w(0, 2), w(1, 0));
  }
  return t.transpose().partialPivLu().solve(f_theta);
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
  if (!state.anchors.empty() && state.anchors.size() != item.first.size())
    throw std::invalid_argument(fmt::format("condition '{}': {} anchors restored for {} targets", item.name,
                                            state.anchors.size(), item.first.size()));
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
  if (item.kind == ConditionKind::bind) {  // the bodies' points at activation
    item.anchors.clear();
    for (int first : item.first) {
      NodeVector anchor = NodeVector::Zero();
      anchor.head<6>() = x.segment<6>(first);
      item.anchors.push_back(anchor);
    }
    return;
  }
  if (item.body && item.kind == ConditionKind::load) {
    // The moment turns a body-fixed vector e_b, normal to the axis at activation: e = Q(theta) e_b.
    const Vec3 theta = x.segment<3>(item.first.front() + 3);
    const Vec3 normal = item.axis.unitOrthogonal();
    NodeVector anchor = NodeVector::Zero();
    anchor.head<6>() = x.segment<6>(item.first.front());
    anchor.segment<3>(6) = model::rotation_matrix(theta).transpose() * normal;
    item.anchors = {anchor};
    item.angle.emplace(item.axis, normal);
    return;
  }
  const NodeVector state =
      item.body ? NodeVector::Zero().eval() : x.segment<beam::kNodeDofs>(item.first.front()).eval();
  if (item.kind == ConditionKind::motion) {
    item.anchors.clear();
    for (int first : item.first) {
      NodeVector anchor = NodeVector::Zero();
      anchor.head(width(item)) = x.segment(first, width(item));
      item.anchors.push_back(anchor);
    }
    if (item.given_pivot) {
      item.pivot = *item.given_pivot;
    } else if (item.body) {
      item.pivot.setZero();
      for (const NodeVector& a : item.anchors)
        item.pivot += a.head<3>() / static_cast<double>(item.anchors.size());
    } else {
      item.pivot = item.anchors[item.anchors.size() / 2].head<3>();
    }
    item.translation.reset(time, Vec3::Zero());
    item.rotation.reset(time, Vec3::Zero());
    item.force.reset(time, Vec3::Zero());
    item.moment.reset(time, 0.0);
    item.director_force.reset(time, NodeVector::Zero());
  } else {
    anchor_moment(item, state);
  }
}

void Conditions::release(int c, double time, const Eigen::VectorXd& residual, double end_time) {
  Item& item = at(c);
  if (item.rigid) throw std::logic_error("release of the rigid condition '" + item.name + "'");
  if (item.kind == ConditionKind::bind) throw std::logic_error("release of the bind '" + item.name + "'");
  if (item.body && item.first.size() > 1 && item.active && item.kind == ConditionKind::motion)
    throw std::logic_error("release of the condition '" + item.name + "' on several bodies");
  NodeVector reaction = NodeVector::Zero();
  reaction.head(width(item)) = residual.segment(item.first.front(), width(item));
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
    for (std::size_t k = 0; k < item.first.size(); ++k)
      for (int d = 0; d < width(item); ++d) {
        if (!item.mask[static_cast<std::size_t>(d)]) continue;
        const auto dof = static_cast<std::size_t>(item.first[k] + d);
        if (owner[dof] >= 0)
          throw std::runtime_error(fmt::format("conditions '{}' and '{}' both prescribe unknown {} of {} {}",
                                               at(owner[dof]).name, item.name, d,
                                               item.body ? "block" : "node", item.blocks[k]));
        owner[dof] = c;
        mask[dof] = true;
      }
  }
  return mask;
}

NodeVector Conditions::prescribed_values(const Item& item, std::size_t k, double time) const {
  const Vec3 rotation = item.rotation.at(time);
  const Eigen::Matrix3d q = rotation_matrix(rotation);
  const NodeVector& anchor = item.anchors[k];
  NodeVector v;
  if (item.body) {
    // theta counts whole turns: composed about one axis, the rotation vectors add.
    const Vec3 theta0 = anchor.segment<3>(3);
    v << item.pivot + item.translation.at(time) + q * (anchor.segment<3>(0) - item.pivot),
        model::rotation_vector(q * model::rotation_matrix(theta0), theta0 + rotation), Vec3::Zero();
    return v;
  }
  v << item.pivot + item.translation.at(time) + q * (anchor.segment<3>(0) - item.pivot),
      q * anchor.segment<3>(3), q * anchor.segment<3>(6);
  return v;
}

void Conditions::apply_prescribed(double time, Eigen::VectorXd& x) const {
  for (const Item& item : items_) {
    if (!item.active || item.kind != ConditionKind::motion) continue;
    for (std::size_t k = 0; k < item.first.size(); ++k) {
      const NodeVector v = prescribed_values(item, k, time);
      for (int d = 0; d < width(item); ++d)
        if (item.mask[static_cast<std::size_t>(d)]) x[item.first[k] + d] = v[d];
    }
  }
}

bool Conditions::applies_load(const Item& item) {
  if (item.rigid || item.kind == ConditionKind::bind) return false;
  return item.kind == ConditionKind::load ? item.active : !item.active;  // a released support ramps down
}

void Conditions::external_force(double time, const Eigen::VectorXd& x, Eigen::VectorXd& f_ext) const {
  for (const Item& item : items_) {
    if (item.kind == ConditionKind::bind && item.active) {
      const std::vector<Vec3> f = bind_forces(item, x);
      for (std::size_t i = 0; i < f.size(); ++i) f_ext.segment<3>(item.first[i]) += f[i];
    }
    if (!applies_load(item)) continue;
    const int base = item.first.front();
    f_ext.segment<3>(base) += item.force.at(time);
    f_ext.segment(base, width(item)) += item.director_force.at(time).head(width(item));
    const double m = item.moment.at(time);
    if (m != 0.0 && item.body) {
      // Work m psi(e), e = Q(theta) e_b: d psi / d theta_k = grad psi . (dQ/dtheta_k) e_b.
      const Vec3 theta = x.segment<3>(base + 3), e_b = item.anchors.front().segment<3>(6);
      const model::RotationDerivatives d = model::rotation_derivatives(theta, false);
      const Vec3 grad = item.angle->gradient(d.q * e_b);
      for (int k = 0; k < 3; ++k)
        f_ext[base + 3 + k] += m * grad.dot(d.first[static_cast<std::size_t>(k)] * e_b);
    } else if (m != 0.0) {
      const int v = base + 3 + 3 * item.director;
      f_ext.segment<3>(v) += m * item.angle->gradient(x.segment<3>(v));
    }
  }
}

void Conditions::add_load_tangent(double time, const Eigen::VectorXd& x,
                                  solver::SparseAssembler& assembler) const {
  for (const Item& item : items_) {
    if (item.kind == ConditionKind::bind && item.active) {
      // -d f_i / d c_j = k P (delta_ij - 1/n): constant.
      const auto n = static_cast<Eigen::Index>(item.first.size());
      Eigen::MatrixXd k = Eigen::MatrixXd::Zero(6 * n, 6 * n);
      for (Eigen::Index i = 0; i < n; ++i)
        for (Eigen::Index j = 0; j < n; ++j)
          for (int d = 0; d < 3; ++d)
            if (item.mask[static_cast<std::size_t>(d)])
              k(6 * i + d, 6 * j + d) =
                  item.stiffness * ((i == j ? 1.0 : 0.0) - 1.0 / static_cast<double>(n));
      assembler.add(item.blocks, k);
    }
    if (!applies_load(item)) continue;
    const double m = item.moment.at(time);
    if (m == 0.0) continue;
    if (item.body) {
      const int base = item.first.front();
      const Vec3 e_b = item.anchors.front().segment<3>(6);
      const model::RotationDerivatives d = model::rotation_derivatives(x.segment<3>(base + 3));
      const Vec3 e = d.q * e_b, grad = item.angle->gradient(e);
      const Eigen::Matrix3d hess = item.angle->hessian(e);
      Eigen::Matrix<double, 6, 6> k = Eigen::Matrix<double, 6, 6>::Zero();
      for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t j = 0; j < 3; ++j)
          k(3 + static_cast<int>(i), 3 + static_cast<int>(j)) =
              -m * ((d.first[i] * e_b).dot(hess * (d.first[j] * e_b)) + grad.dot(d.second[i][j] * e_b));
      const int blocks[1] = {item.blocks.front()};
      assembler.add(blocks, k);
      continue;
    }
    const int v = beam::kNodeDofs * item.nodes.front() + 3 + 3 * item.director;
    Eigen::Matrix<double, beam::kNodeDofs, beam::kNodeDofs> k =
        Eigen::Matrix<double, beam::kNodeDofs, beam::kNodeDofs>::Zero();
    k.block<3, 3>(3 + 3 * item.director, 3 + 3 * item.director) = -m * item.angle->hessian(x.segment<3>(v));
    const int nodes[1] = {item.nodes.front()};
    assembler.add(nodes, k);
  }
}

void Conditions::commit(const Eigen::VectorXd& x) {
  for (Item& item : items_) {
    if (!applies_load(item) || !item.angle) continue;
    if (item.body)
      item.angle->commit(model::rotation_matrix(x.segment<3>(item.first.front() + 3)) *
                         item.anchors.front().segment<3>(6));
    else
      item.angle->commit(x.segment<3>(beam::kNodeDofs * item.nodes.front() + 3 + 3 * item.director));
  }
}

SectionForce Conditions::section_force(int c, double time, const Eigen::VectorXd& x,
                                       const Eigen::VectorXd& residual) const {
  const Item& item = at(c);
  const int base = item.first.front();
  SectionForce out;
  if (item.kind == ConditionKind::bind) {
    if (item.active) out.force = bind_forces(item, x).front();
    return out;
  }
  if (item.body) {
    if (applies_load(item)) {
      const NodeVector f = item.director_force.at(time);
      out.force = item.force.at(time) + f.segment<3>(0);
      out.moment = item.moment.at(time) * item.axis + body_moment(x.segment<3>(base + 3), f.segment<3>(3));
      return out;
    }
    if (!item.active) return out;
    const Vec3 centre = item.pivot + item.translation.at(time);
    for (int first : item.first) {
      const Vec3 f = residual.segment<3>(first);
      out.force += f;
      out.moment += (x.segment<3>(first) - centre).cross(f) +
                    body_moment(x.segment<3>(first + 3), residual.segment<3>(first + 3));
    }
    return out;
  }
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
