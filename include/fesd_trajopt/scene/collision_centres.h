#pragma once

#include <memory>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/kinematics/forward_kinematics.h"
#include "fesd_trajopt/kinematics/sphere_derivatives.h"

namespace fesd {

/// A collision body's centre as a function of the state x: a free body's position plus a fixed
/// offset (linear in x), a turning body's position plus its offset turned by the body's yaw, or a
/// robot sphere's centre (forward kinematics of the joint coordinates q = x.head(nq)).
struct CollisionCentre {
  enum class Source { kFreeBody, kRobotSphere, kTurningBody };
  Source source;
  int index;  ///< a free body: the state index of its first coordinate; robot sphere: the sphere
  /// A free body's sphere: its centre's offset from the body's position, in the body's frame.
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  /// A turning body's: the length rho that scales its turn coordinate, s = rho * yaw, the state
  /// coordinate after its position (Scene: the metric of its limit surface made the identity).
  double turning_radius = 0.0;
};

/// Evaluates collision centres and their derivatives in the few state coordinates each depends on
/// (its variables: a free body's coordinates, a sphere's chain of joints), for both kinds alike.
/// Centres are 3-vectors; in a planar scene (dimension 2) z and its derivatives are 0, which is
/// exact for a planar robot (isPlanar: its spheres keep their z).
class CentreEvaluator {
 public:
  /// `robot` may be null (no robot spheres); q is x's first robot->numCoordinates() entries.
  CentreEvaluator(std::shared_ptr<const KinematicModel> robot, int dimension);
  CentreEvaluator(const CentreEvaluator&) = delete;  // its current configuration is its own
  CentreEvaluator& operator=(const CentreEvaluator&) = delete;

  int dimension() const { return dimension_; }
  const KinematicModel* robot() const { return robot_.get(); }
  /// The state indices a centre depends on, ascending.
  std::vector<int> variables(const CollisionCentre& centre) const;

  /// Forward kinematics at x; every evaluation below refers to the last x set. The kinematics of
  /// up to `kKinematicsKept` configurations are kept: an NLP's value, Jacobian and Hessian visit
  /// its stage points in turn, each at the same q, and each sphere's derivatives there are
  /// computed once, when first asked for, for every pair and derivative order.
  void setState(const double* x);
  static constexpr size_t kKinematicsKept = 1024;
  Eigen::Vector3d position(const CollisionCentre& centre) const;
  /// The derivatives below are written into their last argument, which keeps its memory when it
  /// has their size already: the NLP's evaluations call them per pair and stage point.
  /// dp/dx: 3 x variables(centre).size().
  void jacobian(const CollisionCentre& centre, Eigen::Matrix3Xd& into) const;
  /// The Hessian of w . p(x) in the centre's variables (0 for a translating free body).
  void weightedHessian(const CollisionCentre& centre, const Eigen::Vector3d& w,
                       Eigen::MatrixXd& into) const;
  /// The derivative of weightedHessian along v (in the centre's variables, fixed w).
  void weightedThirdDerivative(const CollisionCentre& centre, const Eigen::Vector3d& w,
                               const Eigen::VectorXd& v, Eigen::MatrixXd& into) const;

 private:
  /// Forward kinematics at one q and the derivatives of the spheres asked for there (the first
  /// `sphere_count` of `spheres`; the rest keep their memory for the next use).
  struct Configuration {
    Eigen::VectorXd q;
    KinematicData data;
    std::vector<std::pair<int, SphereDerivatives>> spheres;
    size_t sphere_count = 0;
  };
  /// A robot sphere's derivatives at the current q.
  const SphereDerivatives& sphereDerivatives(int sphere) const;
  Eigen::Vector3d inPlane(Eigen::Vector3d w) const;

  std::shared_ptr<const KinematicModel> robot_;
  int dimension_;
  /// The configurations seen (the first `used_` of `kept_`; all forgotten at once when it is
  /// full, their memory reused), by a hash of q's bits; `current_` is the last x's.
  std::vector<Configuration> kept_;
  size_t used_ = 0;
  std::unordered_multimap<size_t, int> kept_by_hash_;
  Configuration* current_ = nullptr;
  const double* free_state_ = nullptr;  ///< the x of the last setState (not owned)
};

}  // namespace fesd
