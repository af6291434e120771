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

/// A collision body of a robot scene: a free body of the disc scene or a sphere of the robot.
struct CollisionBody {
  std::string name;  ///< the body's name, or "<link>/sphere_<k>"
  double radius;
  CollisionCentre centre;
  int sphere = -1;  ///< the robot sphere, -1 for a free body
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
  RobotScene(std::shared_ptr<const KinematicModel> robot, Eigen::VectorXd q0, DiscScene discs);

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

  /// The free bodies first, in the disc scene's order, then every robot sphere.
  const std::vector<CollisionBody>& collisionBodies() const { return collision_bodies_; }
  int sphereBody(int sphere) const { return discs_.bodies().size() + sphere; }

  /// Every pair that may touch. Free bodies pair as in DiscScene::allPairs; a robot sphere
  /// pairs with every free body, and, when it moves, with every obstacle and wall; spheres
  /// pair with each other only with self_collision, and then only on non-adjacent links
  /// (neither's joint the other's or its parent) not disabled and apart at the start. Spheres
  /// on the same link never pair.
  std::vector<RobotPair> allPairs() const;
  std::string pairName(const RobotPair& pair) const;
  /// The names of a pair's two sides: the collision body's, then the other's.
  std::pair<std::string, std::string> pairSides(const RobotPair& pair) const;
  /// The constraint value of one pair at a state (> 0: apart).
  double constraintValue(const RobotPair& pair, const Eigen::VectorXd& x) const;
  /// The signed gap between the pair's surfaces at x (negative: overlap).
  double pairGap(const RobotPair& pair, const Eigen::VectorXd& x) const;

  /// The DCS with the given pairs as its constraints, in that order.
  std::shared_ptr<const DcsModel> model(const std::vector<RobotPair>& pairs) const;

 private:
  CentrePair centrePair(const RobotPair& pair) const;
  bool linksMayCollide(int sphere_a, int sphere_b) const;

  std::shared_ptr<const KinematicModel> robot_;
  Eigen::VectorXd q0_;
  DiscScene discs_;
  std::vector<CollisionBody> collision_bodies_;
};

}  // namespace fesd
