#include "fesd_trajopt/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Geometry>

#include "fesd_trajopt/kinematics/reach.h"

namespace fesd {
namespace {

Eigen::Vector3d padded(const Eigen::VectorXd& v) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  p.head(v.size()) = v;
  return p;
}

}  // namespace

Footprint footprintOf(const SceneBody& body) {
  Footprint footprint;
  for (const FreeBodySphere& sphere : body.spheres) {
    footprint.centres.push_back(sphere.offset.head<2>());
    footprint.radii.push_back(sphere.radius);
  }
  if (body.spheres.empty()) footprint = {{Eigen::Vector2d::Zero()}, {body.radius}};
  return footprint;
}

double boundingRadius(const SceneBody& body) {
  if (body.spheres.empty()) return body.radius;
  double radius = 0.0;
  for (const FreeBodySphere& sphere : body.spheres) {
    radius = std::max(radius, sphere.offset.norm() + sphere.radius);
  }
  return radius;
}

void turnAboutPressureCentre(SceneBody& body, double turning_radius) {
  const Eigen::Vector2d centre = pressureCentre(footprintOf(body));
  for (FreeBodySphere& sphere : body.spheres) sphere.offset.head<2>() -= centre;
  body.position.head<2>() += Eigen::Rotation2Dd(body.yaw) * centre;
  body.turns = true;
  body.turning_radius = turning_radius > 0.0
                            ? turning_radius
                            : limitSurfaceRadius(footprintOf(body), Eigen::Vector2d::Zero());
}

namespace {

constexpr double kMaxYaw = 1e4;  // radians: s = rho yaw stays far from overflow

}  // namespace

std::string turningBodyProblem(const SceneBody& body) {
  if (!body.turns) return "";
  if (body.actuated) return "turns and is actuated: only passive bodies turn";
  if (body.spheres.size() < 2) {
    return "turns but is one sphere, the same at every yaw: give it several spheres";
  }
  if (!(std::fabs(body.yaw) <= kMaxYaw)) return "has a yaw that is not finite or beyond 1e4 rad";
  const double size = boundingRadius(body);
  if (!(body.turning_radius >= 1e-3 * size && body.turning_radius <= 1e3 * size)) {
    return "needs a turning radius within 1e-3 to 1e3 times its size (by default its "
           "footprint's limitSurfaceRadius)";
  }
  const Footprint footprint = footprintOf(body);
  double extent = 0.0;
  for (size_t k = 0; k < footprint.centres.size(); ++k) {
    extent = std::max(extent, footprint.centres[k].norm() + footprint.radii[k]);
  }
  if (pressureCentre(footprint).norm() > 1e-6 * extent) {
    return "turns about its position, which must be its spheres' centre of pressure";
  }
  return "";
}

bool namesSide(const std::string& name, const std::string& side) {
  return side == name || side.rfind(name + "/sphere_", 0) == 0;
}

void Scene::setRobot(std::shared_ptr<const KinematicModel> robot, Eigen::VectorXd q0) {
  if (!robot || q0.size() != robot->numCoordinates()) {
    throw std::invalid_argument("Scene: a robot needs one initial value per coordinate");
  }
  robot_ = std::move(robot);
  q0_ = std::move(q0);
}

Scene robotInScene(std::shared_ptr<const KinematicModel> robot, Eigen::VectorXd q0, Scene scene) {
  scene.setRobot(std::move(robot), std::move(q0));
  return scene;
}

int Scene::stateSize() const {
  return stateIndex(static_cast<int>(bodies_.size()));
}

int Scene::stateIndex(int body) const {
  int index = numJoints();
  for (int b = 0; b < body; ++b) index += coordinates(b);
  return index;
}

double Scene::turningRadius(int body) const {
  const SceneBody& b = bodies_.at(body);
  return b.turns ? b.turning_radius : 0.0;
}

double Scene::yaw(int body, const Eigen::VectorXd& x) const {
  if (!bodies_.at(body).turns) return 0.0;
  return x(stateIndex(body) + dimension_) / turningRadius(body);
}

int Scene::controlSize() const {
  int actuated = 0;
  for (const SceneBody& body : bodies_) actuated += body.actuated;
  return numJoints() + dimension_ * actuated;
}

int Scene::controlIndex(int body) const {
  if (!bodies_.at(body).actuated) return -1;
  int actuated_before = 0;
  for (int b = 0; b < body; ++b) actuated_before += bodies_[b].actuated;
  return numJoints() + dimension_ * actuated_before;
}

Eigen::VectorXd Scene::initialState() const {
  Eigen::VectorXd x(stateSize());
  x.head(numJoints()) = q0_;
  for (int b = 0; b < static_cast<int>(bodies_.size()); ++b) {
    x.segment(stateIndex(b), dimension_) = bodies_[b].position;
    if (bodies_[b].turns) x(stateIndex(b) + dimension_) = turningRadius(b) * bodies_[b].yaw;
  }
  return x;
}

void Scene::setInitialState(const Eigen::VectorXd& x) {
  if (x.size() != stateSize()) throw std::invalid_argument("Scene: a state of the wrong size");
  q0_ = x.head(numJoints());
  for (int b = 0; b < static_cast<int>(bodies_.size()); ++b) {
    bodies_[b].position = x.segment(stateIndex(b), dimension_);
    bodies_[b].yaw = yaw(b, x);
  }
}

std::vector<CollisionBody> Scene::collisionBodies() const {
  std::vector<CollisionBody> result;
  for (int b = 0; b < static_cast<int>(bodies_.size()); ++b) {
    const SceneBody& body = bodies_[b];
    CollisionCentre centre{CollisionCentre::Source::kFreeBody, stateIndex(b)};
    if (body.turns) {
      centre.source = CollisionCentre::Source::kTurningBody;
      centre.turning_radius = turningRadius(b);
    }
    if (body.spheres.empty()) result.push_back({body.name, body.radius, centre, -1, b});
    for (const FreeBodySphere& sphere : body.spheres) {
      CollisionCentre moved = centre;
      moved.offset = sphere.offset;
      result.push_back({sphere.name, sphere.radius, moved, -1, b});
    }
  }
  for (int s = 0; robot_ && s < static_cast<int>(robot_->spheres.size()); ++s) {
    const KinematicSphere& sphere = robot_->spheres[s];
    result.push_back({sphere.name, sphere.radius, {CollisionCentre::Source::kRobotSphere, s}, s});
  }
  return result;
}

int Scene::freeCollisionBodies() const {
  int count = 0;
  for (const SceneBody& body : bodies_) count += std::max<int>(1, body.spheres.size());
  return count;
}

int Scene::sphereBody(int sphere) const {
  return freeCollisionBodies() + sphere;
}

std::vector<int> Scene::freeBodyCollisionBodies(int body) const {
  std::vector<int> found;
  int first = 0;
  for (int b = 0; b < body; ++b) first += std::max<int>(1, bodies_[b].spheres.size());
  for (int k = 0; k < std::max<int>(1, bodies_.at(body).spheres.size()); ++k) {
    found.push_back(first + k);
  }
  return found;
}

bool Scene::linksMayCollide(int sphere_a, int sphere_b) const {
  const KinematicLink& a = robot_->links[robot_->spheres[sphere_a].link];
  const KinematicLink& b = robot_->links[robot_->spheres[sphere_b].link];
  if (a.joint == b.joint) return false;  // one rigid body: they never move apart
  const auto parent = [&](int joint) { return joint < 0 ? -2 : robot_->joints[joint].parent; };
  if (parent(a.joint) == b.joint || parent(b.joint) == a.joint) return false;  // adjacent
  for (const auto& [first, second] : disabled_link_pairs) {
    if ((first == a.name && second == b.name) || (first == b.name && second == a.name)) {
      return false;
    }
  }
  return true;
}

std::vector<ContactPair> Scene::allPairs() const {
  std::vector<ContactPair> pairs;
  const std::vector<CollisionBody> bodies = collisionBodies();
  std::vector<int> supports;
  for (int b = 0; b < static_cast<int>(bodies_.size()); ++b) supports.push_back(supportOf(b));
  const int all = static_cast<int>(bodies.size());
  const int obstacles = static_cast<int>(obstacles_.size());
  const int walls = static_cast<int>(walls_.size());
  const Eigen::VectorXd x0 = initialState();
  for (int i = 0; i < all; ++i) {
    const int sphere = bodies[i].sphere;
    // A sphere fixed to the world (e.g. a base plate) is an obstacle to the free bodies only.
    const bool moves = sphere < 0 || robot_->links[robot_->spheres[sphere].link].joint >= 0;
    for (int j = i + 1; j < all; ++j) {
      const int other = bodies[j].sphere;
      if (other < 0 && bodies[j].free_body == bodies[i].free_body) continue;
      const ContactPair pair{i, ContactPair::Kind::kBody, j};
      if (other >= 0 && sphere >= 0) {
        if (!self_collision || !linksMayCollide(sphere, other)) continue;
        if (pairGap(pair, x0) < 0.0) continue;  // overlapping at the start: meant to
      }
      pairs.push_back(pair);
    }
    if (!moves) continue;
    for (int o = 0; o < obstacles; ++o) pairs.push_back({i, ContactPair::Kind::kObstacle, o});
    for (int w = 0; w < walls; ++w) {
      // A body slides on its support: a joint, no contact.
      if (bodies[i].free_body < 0 || supports[bodies[i].free_body] != w) {
        pairs.push_back({i, ContactPair::Kind::kWall, w});
      }
    }
  }
  return pairs;
}

double Scene::jointUnit(int joint) const {
  const KinematicJoint& j = robot_->joints.at(joint);
  return j.type == JointType::kPrismatic ? length_unit : j.coordinate_scale;
}

bool Scene::isLevel(int wall) const {
  return dimension_ == 3 && std::fabs(std::fabs(walls_.at(wall).normal(2)) - 1.0) <= 1e-12;
}

std::pair<double, double> Scene::lowestGap(int body, int wall) const {
  const Eigen::VectorXd x0 = initialState();
  const std::vector<CollisionBody> bodies = collisionBodies();
  double gap = std::numeric_limits<double>::infinity(), radius = 0.0;
  for (int c : freeBodyCollisionBodies(body)) {
    const double sphere_gap = pairGap({c, ContactPair::Kind::kWall, wall}, x0);
    if (sphere_gap < gap) {
      gap = sphere_gap;
      radius = bodies[c].radius;
    }
  }
  return {gap, radius};
}

std::vector<int> Scene::restingWalls(int body) const {
  std::vector<int> resting;
  for (int w = 0; w < static_cast<int>(walls_.size()); ++w) {
    if (!isLevel(w)) continue;
    const auto [gap, radius] = lowestGap(body, w);
    if (std::fabs(gap) <= kRestingTolerance * radius) resting.push_back(w);
  }
  return resting;
}

int Scene::supportOf(int body) const {
  const SceneBody& b = bodies_.at(body);
  if (dimension_ != 3 || b.support == SupportMode::kNone) return -1;
  if (b.support == SupportMode::kWall) return b.support_wall;
  const std::vector<int> resting = restingWalls(body);
  return resting.size() == 1 ? resting.front() : -1;
}

std::string Scene::pairName(const ContactPair& pair) const {
  const auto [body, other] = pairSides(pair);
  return body + "/" + other;
}

std::pair<std::string, std::string> Scene::pairSides(const ContactPair& pair) const {
  const std::vector<CollisionBody> bodies = collisionBodies();
  const std::string& body = bodies.at(pair.body).name;
  switch (pair.kind) {
    case ContactPair::Kind::kBody:
      return {body, bodies.at(pair.other).name};
    case ContactPair::Kind::kObstacle:
      return {body, obstacles_.at(pair.other).name};
    case ContactPair::Kind::kWall:
      return {body, walls_.at(pair.other).name};
  }
  return {body, ""};
}

double Scene::collisionRadius(int index) const {
  if (index >= 0) {
    for (const SceneBody& body : bodies_) {
      const int count = std::max<int>(1, body.spheres.size());
      if (index < count) return body.spheres.empty() ? body.radius : body.spheres[index].radius;
      index -= count;
    }
    if (robot_ && index < static_cast<int>(robot_->spheres.size())) {
      return robot_->spheres[index].radius;
    }
  }
  throw std::out_of_range("Scene::collisionRadius: no collision body of that index");
}

double Scene::pairSize(const ContactPair& pair) const {
  const double radius = collisionRadius(pair.body);
  switch (pair.kind) {
    case ContactPair::Kind::kBody:
      return radius + collisionRadius(pair.other);
    case ContactPair::Kind::kObstacle:
      return radius + obstacles_.at(pair.other).radius;
    case ContactPair::Kind::kWall:
      return radius;
  }
  return radius;
}

CentrePair Scene::centrePair(const std::vector<CollisionBody>& bodies,
                             const ContactPair& pair) const {
  const CollisionBody& a = bodies.at(pair.body);
  CentrePair result;
  result.a = a.centre;
  switch (pair.kind) {
    case ContactPair::Kind::kBody: {
      const CollisionBody& b = bodies.at(pair.other);
      result.kind = CentrePair::Kind::kCentre;
      result.b = b.centre;
      result.constant = (a.radius + b.radius) * (a.radius + b.radius);
      break;
    }
    case ContactPair::Kind::kObstacle: {
      const SceneObstacle& o = obstacles_.at(pair.other);
      result.kind = CentrePair::Kind::kPoint;
      result.point = padded(o.position);
      result.constant = (a.radius + o.radius) * (a.radius + o.radius);
      break;
    }
    case ContactPair::Kind::kWall: {
      const SceneWall& w = walls_.at(pair.other);
      result.kind = CentrePair::Kind::kWall;
      result.point = padded(w.normal);
      result.constant = w.offset + a.radius;
      break;
    }
  }
  return result;
}

double Scene::constraintValue(const ContactPair& pair, const Eigen::VectorXd& x) const {
  CentreEvaluator evaluator(robot_, dimension_);
  evaluator.setState(x.data());
  return centrePairValue(evaluator, centrePair(collisionBodies(), pair));
}

double Scene::pairGap(const ContactPair& pair, const Eigen::VectorXd& x) const {
  return pairGaps({pair}, x)[0];
}

std::vector<double> Scene::pairGaps(const std::vector<ContactPair>& pairs,
                                    const Eigen::VectorXd& x) const {
  const std::vector<CollisionBody> bodies = collisionBodies();
  CentreEvaluator evaluator(robot_, dimension_);
  evaluator.setState(x.data());  // one forward kinematics for all pairs
  std::vector<double> gaps;
  gaps.reserve(pairs.size());
  for (const ContactPair& pair : pairs) {
    const CollisionBody& body = bodies.at(pair.body);
    const Eigen::Vector3d p = evaluator.position(body.centre);
    switch (pair.kind) {
      case ContactPair::Kind::kBody: {
        const CollisionBody& other = bodies.at(pair.other);
        gaps.push_back((p - evaluator.position(other.centre)).norm() -
                       (body.radius + other.radius));
        break;
      }
      case ContactPair::Kind::kObstacle: {
        const SceneObstacle& o = obstacles_.at(pair.other);
        gaps.push_back((p - padded(o.position)).norm() - (body.radius + o.radius));
        break;
      }
      case ContactPair::Kind::kWall: {
        const SceneWall& w = walls_.at(pair.other);
        gaps.push_back(padded(w.normal).dot(p) - w.offset - body.radius);
        break;
      }
    }
  }
  return gaps;
}

CentrePairSystem Scene::centreSystem(const std::vector<ContactPair>& pairs) const {
  if (dimension_ != 2 && dimension_ != 3) {
    throw std::invalid_argument("Scene: dimension must be 2 or 3");
  }
  for (const SceneBody& body : bodies_) {
    if (body.position.size() != dimension_) {
      throw std::invalid_argument("Scene: body '" + body.name + "' has the wrong dimension");
    }
    const std::string turning = turningBodyProblem(body);
    if (!turning.empty()) throw std::invalid_argument("Scene: body '" + body.name + "' " + turning);
  }
  CentrePairSystem system;
  system.robot = robot_;
  system.dimension = dimension_;
  system.state_size = stateSize();
  system.control_size = controlSize();
  for (int j = 0; j < numJoints(); ++j) system.actuation.emplace_back(j, j);
  for (int b = 0; b < static_cast<int>(bodies_.size()); ++b) {
    if (!bodies_[b].actuated) continue;
    for (int d = 0; d < dimension_; ++d) {
      system.actuation.emplace_back(stateIndex(b) + d, controlIndex(b) + d);
    }
  }
  // A revolute joint's motion weighs as an arc at the robot's reach (units of length, as the
  // positions'); a support holds its body's height: the contacts' normal force goes into it.
  system.mobility.assign(system.state_size, 1.0);
  if (robot_) {
    const double reach = robotReach(*robot_);
    for (int j = 0; j < numJoints(); ++j) {
      if (robot_->joints[j].type != JointType::kPrismatic) {
        system.mobility[j] = 1.0 / (reach * reach);
      }
    }
  }
  for (int b : supportedBodies()) system.mobility[stateIndex(b) + 2] = 0.0;
  const std::vector<CollisionBody> bodies = collisionBodies();
  system.constraint_scales.resize(pairs.size());
  for (size_t k = 0; k < pairs.size(); ++k) {
    system.pairs.push_back(centrePair(bodies, pairs[k]));
    // |grad_p c| on the boundary; for a robot sphere in q it is that times the lever arm, which
    // depends on the configuration.
    system.constraint_scales(k) =
        pairs[k].kind == ContactPair::Kind::kWall ? 1.0 : 2.0 * pairSize(pairs[k]);
  }
  return system;
}

std::shared_ptr<const DcsModel> Scene::model(const std::vector<ContactPair>& pairs) const {
  return centrePairModel(centreSystem(pairs), "scene");
}

std::vector<int> Scene::supportedBodies() const {
  std::vector<int> supported;
  for (int b = 0; b < static_cast<int>(bodies_.size()); ++b) {
    if (supportOf(b) >= 0) supported.push_back(b);
  }
  return supported;
}

SupportLiftRates Scene::supportLiftRates(const std::vector<ContactPair>& pairs,
                                         const std::vector<int>& bodies_asked) const {
  // A body no pair touches has the rate 0 at every state: no row for it.
  const std::vector<CollisionBody> bodies = collisionBodies();
  std::vector<bool> touched(bodies_.size(), false);
  for (const ContactPair& pair : pairs) {
    if (bodies[pair.body].free_body >= 0) touched[bodies[pair.body].free_body] = true;
    if (pair.kind == ContactPair::Kind::kBody && bodies[pair.other].free_body >= 0) {
      touched[bodies[pair.other].free_body] = true;
    }
  }
  SupportLiftRates lift;
  std::vector<std::pair<int, double>> held;
  for (int b : bodies_asked) {
    if (supportOf(b) < 0 || !touched[b]) continue;
    lift.bodies.push_back(b);
    held.emplace_back(stateIndex(b) + 2, walls_[supportOf(b)].normal(2));
  }
  if (!held.empty()) lift.rates = heldCoordinateRates(centreSystem(pairs), held);
  return lift;
}

}  // namespace fesd
