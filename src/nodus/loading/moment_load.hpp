#pragma once
/// A moment applied to a 9-dof cross-section about a fixed axis.
///
/// The section has no rotation unknown, so the moment acts through one of its directors v: its work is
/// M phi(v), with phi the angle of the projection of v on the plane normal to the axis, counted continuously
/// (several turns are possible). The generalised force on v is M dphi/dv, whose moment about the section
/// centre, v x M dphi/dv, is exactly M along the axis. The load is conservative, so its tangent is symmetric.
/// For a rotation about the axis this is the dead moment of a rigid section; docs/model.md discusses the 3D
/// case.

#include <Eigen/Core>

namespace nodus::loading {

using Vec3 = Eigen::Vector3d;

class AxisAngle {
 public:
  /// Everything an AxisAngle holds: the axis, the basis b1, b2 of the plane normal to it in which the angle
  /// is measured (b1 along the director at activation), and the committed angle [rad] (counting turns).
  struct State {
    Vec3 axis = Vec3::UnitZ();
    Vec3 b1 = Vec3::UnitX();
    Vec3 b2 = Vec3::UnitY();
    double committed = 0.0;
  };

  /// `axis`: unit vector; `v0`: the director at activation, not parallel to the axis.
  AxisAngle(const Vec3& axis, const Vec3& v0);
  /// The AxisAngle whose state() is `state` (a saved state).
  explicit AxisAngle(const State& state)
      : axis_(state.axis), b1_(state.b1), b2_(state.b2), committed_(state.committed) {}
  State state() const { return {axis_, b1_, b2_, committed_}; }

  /// Angle of v about the axis [rad], continuous from the committed angle (valid while v turns by less than
  /// pi between two commits).
  double angle(const Vec3& v) const;
  /// d angle / d v [1/length of v].
  Vec3 gradient(const Vec3& v) const;
  /// d^2 angle / d v^2.
  Eigen::Matrix3d hessian(const Vec3& v) const;
  /// Accepts v as the converged director (updates the turn count).
  void commit(const Vec3& v) { committed_ = angle(v); }

 private:
  Vec3 axis_, b1_, b2_;
  double committed_ = 0.0;
};

}  // namespace nodus::loading
