#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/kinematics/kinematic_model.h"
#include "fesd_trajopt/model/dcs_model.h"
#include "fesd_trajopt/scene/centre_pair_model.h"
#include "fesd_trajopt/scene/limit_surface.h"

namespace fesd {

/// One of several spheres a free body carries (a free link of a URDF): it moves with the body's
/// position (and its yaw, when the body turns).
struct FreeBodySphere {
  std::string name;        ///< "<link>/sphere_<k>"
  Eigen::Vector3d offset;  ///< from the body's position, in its frame
  double radius;
};

/// What a free body of a spatial scene slides on (design.md, "Bodies on a support"): the level
/// wall it rests on (kAuto), the wall SceneBody::support_wall (kWall), or nothing: it floats and
/// every wall is a contact pair of it (kNone).
enum class SupportMode { kAuto, kNone, kWall };

/// A body rests on a wall when its lowest sphere's gap to it is within this fraction of that
/// sphere's radius (either side).
constexpr double kRestingTolerance = 1e-2;
/// A plan lifts a supported body when its lift (planning/support_check.h) exceeds this fraction of
/// the body's radius: the body floats from then on and its pairs with the wall are modelled.
constexpr double kSupportLiftTolerance = 1e-3;

/// A free disc (2-D) or sphere (3-D): a link on a translation joint from the world, or on a
/// planar joint when it turns. Actuated bodies are velocity-controlled (pdot = u); passive ones
/// only move when pushed.
struct SceneBody {
  std::string name;
  double radius = 1.0;
  Eigen::VectorXd position;  ///< initial position; a turning body's centre of pressure
  bool actuated = false;
  /// The spheres it carries when several; empty: it is one sphere of `radius` at `position`.
  std::vector<FreeBodySphere> spheres = {};
  /// Turns about z as it is pushed, quasi-statically with an ellipsoidal limit surface
  /// (limit_surface.h; docs/design.md): its state holds s = rho yaw after its position, so that
  /// the projection in the metric diag(1, 1, rho^2) is the plain one. Passive bodies only.
  bool turns = false;
  double yaw = 0.0;  ///< initial yaw (a turning body's)
  /// rho (> 0 when it turns): by default its footprint's limitSurfaceRadius (the request layer
  /// sets that).
  double turning_radius = 0.0;
  /// A body on a level wall slides on it as on a planar joint (Scene::supportOf): its height
  /// stays, the contacts' forces move it along the wall (the wall takes their normal part) and
  /// turn it about the wall's normal; the (body, wall) pair is no complementarity.
  SupportMode support = SupportMode::kAuto;
  int support_wall = -1;  ///< with kWall: the wall
};

/// A fixed disc or sphere.
struct SceneObstacle {
  std::string name;
  double radius = 1.0;
  Eigen::VectorXd position;
};

/// A fixed half-space boundary: bodies stay on the side  normal . p >= offset  (normal of unit
/// length, pointing into the free side).
struct SceneWall {
  std::string name;
  Eigen::VectorXd normal;
  double offset = 0.0;
};

/// What collides: a free body (or one of its spheres) or a sphere of the robot.
struct CollisionBody {
  std::string name;  ///< the body's name, or "<link>/sphere_<k>"
  double radius;
  CollisionCentre centre;
  int sphere = -1;     ///< the robot sphere, -1 for a free body's
  int free_body = -1;  ///< the free body it belongs to, -1 for a robot sphere
};

/// Per supported body a pair touches (`bodies`, ascending), on Scene::model(pairs)'s
/// (x, u, lambda): the rate at which the pairs' forces would move it along its support's normal
/// were its height free (heldCoordinateRates); rates null without such a body.
struct SupportLiftRates {
  std::vector<int> bodies;
  std::shared_ptr<const SmoothFunction> rates;
};

/// A contact the model may enforce: collision body `body` (Scene::collisionBodies) against
/// another collision body, an obstacle or a wall.
struct ContactPair {
  enum class Kind { kBody, kObstacle, kWall };
  int body;
  Kind kind;
  int other;  ///< index into the collision bodies, obstacles or walls

  bool operator==(const ContactPair& o) const {
    return body == o.body && kind == o.kind && other == o.other;
  }
};

/// The radius of the disc (sphere) about a body's position that holds its spheres (its radius
/// when it is one sphere).
double boundingRadius(const SceneBody& body);
/// A turning body's footprint in its frame (limit_surface.h): its spheres', or its own disc.
Footprint footprintOf(const SceneBody& body);
/// Makes a body of spheres turn about their centre of pressure: moves its position there (its
/// offsets turned by its yaw) and its offsets with it, and sets its turning radius to the
/// footprint's limitSurfaceRadius unless `turning_radius` > 0 is given.
void turnAboutPressureCentre(SceneBody& body, double turning_radius = 0.0);
/// What makes a body unfit to turn ("" if nothing, or if it does not turn): actuated, one sphere
/// only, a yaw that is not finite or beyond 1e4 rad, a turning radius not within 1e-3 to 1e3
/// times its bounding radius, spheres whose centre of pressure is not its position.
std::string turningBodyProblem(const SceneBody& body);

/// Whether `name` names the collision body `side`: as that body, obstacle or wall, or as the
/// link (or free body) whose sphere `<name>/sphere_<k>` it is.
bool namesSide(const std::string& name, const std::string& side);

/// Free bodies, obstacles, walls and optionally a robot (a KinematicModel, velocity-controlled:
/// qdot = u_q), in the plane or in space, as one projected dynamical system. The state is
/// x = (q, the free bodies' positions), the controls u = (u_q, the actuated bodies' velocities),
/// f(x, u) = B u. A free body is a link on a translation joint, a robot sphere hangs on its
/// chain; both are collision bodies (CollisionCentre), so every pair's constraint
///   c = |p_a(x) - p_b(x)|^2 - (r_a + r_b)^2,  |p_a(x) - o|^2 - (r_a + r_o)^2  or
///   n . p_a(x) - offset - r_a
/// is one function of centres whatever they belong to (centrePairModel: exact sparse
/// derivatives). A planar scene (dimension 2) takes the spheres' (x, y), exact for a planar
/// robot (isPlanar).
class Scene {
 public:
  explicit Scene(int dimension) : dimension_(dimension) {}

  int dimension() const { return dimension_; }
  std::vector<SceneBody>& bodies() { return bodies_; }
  const std::vector<SceneBody>& bodies() const { return bodies_; }
  std::vector<SceneObstacle>& obstacles() { return obstacles_; }
  const std::vector<SceneObstacle>& obstacles() const { return obstacles_; }
  std::vector<SceneWall>& walls() { return walls_; }
  const std::vector<SceneWall>& walls() const { return walls_; }

  /// Puts a robot at joints q0 in the scene (one value per coordinate, else invalid_argument).
  void setRobot(std::shared_ptr<const KinematicModel> robot, Eigen::VectorXd q0);
  bool hasRobot() const { return robot_ != nullptr; }
  const KinematicModel& robot() const { return *robot_; }
  const std::shared_ptr<const KinematicModel>& robotPointer() const { return robot_; }
  const Eigen::VectorXd& initialJoints() const { return q0_; }
  int numJoints() const { return robot_ ? robot_->numCoordinates() : 0; }
  /// Self-collision between spheres of non-adjacent links (off by default).
  bool self_collision = false;
  /// Link pairs that never collide (an SRDF's disable_collisions), either order.
  std::vector<std::pair<std::string, std::string>> disabled_link_pairs;
  /// How long one length unit of this scene is in its user's units: 1 for a user's scene, the
  /// length scale for the scene a solve sees (taskInLengthUnits). Messages print lengths in the
  /// user's units (userLength).
  double length_unit = 1.0;
  double userLength(double length) const { return length * length_unit; }
  /// The user's units per unit of joint coordinate j: radians (a revolute joint's
  /// coordinate_scale; 1 in a user's scene) or, for a prismatic joint, length_unit.
  double jointUnit(int joint) const;

  int stateSize() const;
  int controlSize() const;
  /// A free body's state coordinates: its position's, and s = rho yaw when it turns.
  int coordinates(int body) const { return dimension_ + (bodies_.at(body).turns ? 1 : 0); }
  /// First state index of a free body's position.
  int stateIndex(int body) const;
  /// A free body's position at a state of the scene.
  Eigen::VectorXd position(int body, const Eigen::VectorXd& x) const {
    return x.segment(stateIndex(body), dimension_);
  }
  /// A body's rho (SceneBody::turning_radius); 0 if it does not turn.
  double turningRadius(int body) const;
  /// A free body's yaw at a state of the scene (0 for one that does not turn).
  double yaw(int body, const Eigen::VectorXd& x) const;
  /// First control index of a free body's velocity, or -1 for a passive body.
  int controlIndex(int body) const;
  Eigen::VectorXd initialState() const;
  /// Puts the robot's joints and the free bodies at a state of the scene (of stateSize()), which
  /// becomes its initial state (a replan from where a plan's execution got to).
  void setInitialState(const Eigen::VectorXd& x);

  /// The free bodies first, in order (each one, or its spheres), then every robot sphere.
  std::vector<CollisionBody> collisionBodies() const;
  /// The collision body of a robot sphere.
  int sphereBody(int sphere) const;
  /// The collision bodies of a free body (one, or one per sphere).
  std::vector<int> freeBodyCollisionBodies(int body) const;

  /// Every pair that may touch: each collision body with the later ones (never two of one free
  /// body; two robot spheres only with self_collision, on non-adjacent links not disabled and
  /// apart at the start) and, when it moves, with every obstacle and wall.
  std::vector<ContactPair> allPairs() const;
  std::string pairName(const ContactPair& pair) const;
  /// The names of a pair's two sides: the collision body's, then the other's.
  std::pair<std::string, std::string> pairSides(const ContactPair& pair) const;
  /// The length a pair's margins are relative to: the sum of its radii (a wall: the body's).
  double pairSize(const ContactPair& pair) const;
  /// The radius of collision body `index` (collisionBodies()[index].radius without building
  /// them all: pair checks ask for every pair in reach at every point they check).
  double collisionRadius(int index) const;
  /// The constraint value of one pair at a state (> 0: apart).
  double constraintValue(const ContactPair& pair, const Eigen::VectorXd& x) const;
  /// The signed gap between the pair's surfaces at x (negative: overlap).
  double pairGap(const ContactPair& pair, const Eigen::VectorXd& x) const;
  /// pairGap of each pair at x, with one forward kinematics for all.
  std::vector<double> pairGaps(const std::vector<ContactPair>& pairs,
                               const Eigen::VectorXd& x) const;

  /// The DCS with the given pairs as its constraints, in that order.
  std::shared_ptr<const DcsModel> model(const std::vector<ContactPair>& pairs) const;
  /// The rates at which the pairs' forces would lift those of `bodies` that have a support and
  /// that a pair touches off their supports were they free. A support only pushes: a plan keeps
  /// these <= 0.
  SupportLiftRates supportLiftRates(const std::vector<ContactPair>& pairs,
                                    const std::vector<int>& bodies) const;

  /// Whether a wall is level: its normal along +-z (in a spatial scene).
  bool isLevel(int wall) const;
  /// The gap between a free body's lowest sphere and a wall at the start, and that sphere's radius.
  std::pair<double, double> lowestGap(int body, int wall) const;
  /// The level walls a free body rests on at the start (kRestingTolerance).
  std::vector<int> restingWalls(int body) const;
  /// The wall a free body slides on (SceneBody::support): kWall's wall, the one level wall it
  /// rests on (kAuto), else -1 (it floats; always in a planar scene, and for kAuto on two).
  int supportOf(int body) const;
  /// The free bodies with a support (supportOf >= 0), ascending.
  std::vector<int> supportedBodies() const;

 private:
  /// The centre pairs, actuation and mobilities that model(pairs) is made of.
  CentrePairSystem centreSystem(const std::vector<ContactPair>& pairs) const;
  CentrePair centrePair(const std::vector<CollisionBody>& bodies, const ContactPair& pair) const;
  bool linksMayCollide(int sphere_a, int sphere_b) const;
  int freeCollisionBodies() const;

  int dimension_;
  std::vector<SceneBody> bodies_;
  std::vector<SceneObstacle> obstacles_;
  std::vector<SceneWall> walls_;
  std::shared_ptr<const KinematicModel> robot_;
  Eigen::VectorXd q0_;
};

/// `scene` with a robot at joints q0 in it (Scene::setRobot).
Scene robotInScene(std::shared_ptr<const KinematicModel> robot, Eigen::VectorXd q0, Scene scene);

}  // namespace fesd
