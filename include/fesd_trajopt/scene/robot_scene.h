#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/kinematics/kinematic_model.h"
#include "fesd_trajopt/model/dcs_model.h"
#include "fesd_trajopt/scene/centre_pair_model.h"
#include "fesd_trajopt/scene/disc_scene.h"

namespace fesd {

/// A sphere of a free body that carries several (a free link of a URDF): it translates with
/// the body's position and never rotates.
struct FreeBodySphere {
  std::string name;        ///< "<link>/sphere_<k>"
  Eigen::Vector3d offset;  ///< from the body's position
  double radius;
};

/// Whether `name` names the collision body `side`: as that body, obstacle or wall, or as the
/// link (or free body) whose sphere `<name>/sphere_<k>` it is.
bool namesSide(const std::string& name, const std::string& side);

/// A collision body of a robot scene: a free body of the disc scene (or one of its spheres) or a
/// sphere of the robot.
struct CollisionBody {
  std::string name;  ///< the body's name, or "<link>/sphere_<k>"
  double radius;
  CollisionCentre centre;
  int sphere = -1;     ///< the robot sphere, -1 for a free body's
  int free_body = -1;  ///< the free body it belongs to, -1 for a robot sphere
};

/// A contact pair of a robot scene: collision body `body` (RobotScene::collisionBodies) against
/// another collision body, an obstacle or a wall of the disc scene.
struct RobotPair {
  enum class Kind { kBody, kObstacle, kWall };
  int body;
  Kind kind;
  int other;

  bool operator==(const RobotPair& o) const {
    return body == o.body && kind == o.kind && other == o.other;
  }
};

/// A robot (a KinematicModel, velocity-controlled: qdot = u_q) in a disc scene (free bodies,
/// obstacles, walls), as one projected dynamical system. The state is x = (q, the free bodies'
/// positions), the controls u = (u_q, the actuated bodies' velocities). The robot's spheres are
/// collision bodies like the free bodies (CollisionCentre), so every pair's constraint
///   c = |p_a(x) - p_b(x)|^2 - (r_a + r_b)^2  or  n . p_a(x) - offset - r_a
/// is the same function of centres whatever they belong to. A planar scene (dimension 2) takes
/// the spheres' (x, y), exact for a planar robot (isPlanar).
class RobotScene {
 public:
  /// free_body_spheres: per free body (in the disc scene's order, possibly fewer), its spheres
  /// when it carries several; a body without an entry is its one sphere.
  RobotScene(std::shared_ptr<const KinematicModel> robot, Eigen::VectorXd q0, DiscScene discs,
             std::vector<std::vector<FreeBodySphere>> free_body_spheres = {});

  const KinematicModel& robot() const { return *robot_; }
  const std::shared_ptr<const KinematicModel>& robotPointer() const { return robot_; }
  const Eigen::VectorXd& initialJoints() const { return q0_; }
  const DiscScene& discs() const { return discs_; }
  int dimension() const { return discs_.dimension(); }
  int numJoints() const { return robot_->numCoordinates(); }

  /// Self-collision between spheres of non-adjacent links (off by default).
  bool self_collision = false;
  /// Link pairs that never collide (an SRDF's disable_collisions), either order.
  std::vector<std::pair<std::string, std::string>> disabled_link_pairs;

  int stateSize() const { return numJoints() + discs_.stateSize(); }
  int controlSize() const { return numJoints() + discs_.controlSize(); }
  /// First state index of a free body's position.
  int bodyStateIndex(int body) const { return numJoints() + discs_.stateIndex(body); }
  Eigen::VectorXd initialState() const;

  /// The free bodies first, in the disc scene's order (each one, or its spheres), then every
  /// robot sphere.
  const std::vector<CollisionBody>& collisionBodies() const { return collision_bodies_; }
  int sphereBody(int sphere) const { return free_collision_bodies_ + sphere; }
  /// The collision bodies of a free body (one, or one per sphere).
  std::vector<int> freeBodyCollisionBodies(int body) const;
  const std::vector<std::vector<FreeBodySphere>>& freeBodySpheres() const {
    return free_body_spheres_;
  }

  /// Every pair that may touch. Free bodies pair as in DiscScene::allPairs, sphere by sphere
  /// (a free body's own spheres never pair); a robot sphere pairs with every free body, and,
  /// when it moves, with every obstacle and wall; robot spheres pair with each other only with
  /// self_collision, and then only on non-adjacent links (neither's joint the other's or its
  /// parent) not disabled and apart at the start. Spheres on the same link never pair.
  std::vector<RobotPair> allPairs() const;
  std::string pairName(const RobotPair& pair) const;
  /// The names of a pair's two sides: the collision body's, then the other's.
  std::pair<std::string, std::string> pairSides(const RobotPair& pair) const;
  /// The constraint value of one pair at a state (> 0: apart).
  double constraintValue(const RobotPair& pair, const Eigen::VectorXd& x) const;
  /// The signed gap between the pair's surfaces at x (negative: overlap).
  double pairGap(const RobotPair& pair, const Eigen::VectorXd& x) const;
  /// pairGap of each pair at x, with one forward kinematics for all.
  std::vector<double> pairGaps(const std::vector<RobotPair>& pairs, const Eigen::VectorXd& x) const;

  /// The DCS with the given pairs as its constraints, in that order.
  std::shared_ptr<const DcsModel> model(const std::vector<RobotPair>& pairs) const;

 private:
  CentrePair centrePair(const RobotPair& pair) const;
  bool linksMayCollide(int sphere_a, int sphere_b) const;

  std::shared_ptr<const KinematicModel> robot_;
  Eigen::VectorXd q0_;
  DiscScene discs_;
  std::vector<std::vector<FreeBodySphere>> free_body_spheres_;
  std::vector<CollisionBody> collision_bodies_;
  int free_collision_bodies_ = 0;
};

}  // namespace fesd
