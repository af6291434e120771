#include "fesd_trajopt/scene/robot_scene.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace fesd {

bool namesSide(const std::string& name, const std::string& side) {
  return side == name || side.rfind(name + "/sphere_", 0) == 0;
}

RobotScene::RobotScene(std::shared_ptr<const KinematicModel> robot, Eigen::VectorXd q0,
                       DiscScene discs, std::vector<std::vector<FreeBodySphere>> free_body_spheres)
    : robot_(std::move(robot)),
      q0_(std::move(q0)),
      discs_(std::move(discs)),
      free_body_spheres_(std::move(free_body_spheres)) {
  if (!robot_ || q0_.size() != robot_->numCoordinates()) {
    throw std::invalid_argument("RobotScene: q0 needs one value per robot coordinate");
  }
  const int bodies = static_cast<int>(discs_.bodies().size());
  if (static_cast<int>(free_body_spheres_.size()) > bodies) {
    throw std::invalid_argument("RobotScene: spheres given for more free bodies than there are");
  }
  free_body_spheres_.resize(bodies);
  for (int b = 0; b < bodies; ++b) {
    const SceneBody& body = discs_.bodies()[b];
    const CollisionCentre centre{CollisionCentre::Source::kFreeBody, bodyStateIndex(b)};
    if (free_body_spheres_[b].empty()) {
      collision_bodies_.push_back({body.name, body.radius, centre, -1, b});
    }
    for (const FreeBodySphere& sphere : free_body_spheres_[b]) {
      CollisionCentre moved = centre;
      moved.offset = sphere.offset;
      collision_bodies_.push_back({sphere.name, sphere.radius, moved, -1, b});
    }
  }
  free_collision_bodies_ = static_cast<int>(collision_bodies_.size());
  for (int s = 0; s < static_cast<int>(robot_->spheres.size()); ++s) {
    const KinematicSphere& sphere = robot_->spheres[s];
    collision_bodies_.push_back(
        {sphere.name, sphere.radius, {CollisionCentre::Source::kRobotSphere, s}, s});
  }
}

std::vector<int> RobotScene::freeBodyCollisionBodies(int body) const {
  std::vector<int> found;
  for (int i = 0; i < free_collision_bodies_; ++i) {
    if (collision_bodies_[i].free_body == body) found.push_back(i);
  }
  return found;
}

Eigen::VectorXd RobotScene::initialState() const {
  Eigen::VectorXd x(stateSize());
  x << q0_, discs_.initialState();
  return x;
}

bool RobotScene::linksMayCollide(int sphere_a, int sphere_b) const {
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

std::vector<RobotPair> RobotScene::allPairs() const {
  std::vector<RobotPair> pairs;
  const int all = static_cast<int>(collision_bodies_.size());
  const int obstacles = static_cast<int>(discs_.obstacles().size());
  const int walls = static_cast<int>(discs_.walls().size());
  const Eigen::VectorXd x0 = initialState();
  for (int i = 0; i < all; ++i) {
    const int sphere = collision_bodies_[i].sphere;
    // A sphere fixed to the world (e.g. a base plate) is an obstacle to the free bodies only.
    const bool moves = sphere < 0 || robot_->links[robot_->spheres[sphere].link].joint >= 0;
    for (int j = i + 1; j < all; ++j) {
      const int other = collision_bodies_[j].sphere;
      if (other < 0 && collision_bodies_[j].free_body == collision_bodies_[i].free_body) continue;
      if (other >= 0 && sphere >= 0) {
        if (!self_collision || !linksMayCollide(sphere, other)) continue;
        const RobotPair pair{i, RobotPair::Kind::kBody, j};
        if (pairGap(pair, x0) < 0.0) continue;  // overlapping at the start: meant to
        pairs.push_back(pair);
        continue;
      }
      pairs.push_back({i, RobotPair::Kind::kBody, j});
    }
    if (!moves) continue;
    for (int o = 0; o < obstacles; ++o) pairs.push_back({i, RobotPair::Kind::kObstacle, o});
    for (int w = 0; w < walls; ++w) pairs.push_back({i, RobotPair::Kind::kWall, w});
  }
  return pairs;
}

std::string RobotScene::pairName(const RobotPair& pair) const {
  const auto [body, other] = pairSides(pair);
  return body + "/" + other;
}

std::pair<std::string, std::string> RobotScene::pairSides(const RobotPair& pair) const {
  const std::string& body = collision_bodies_.at(pair.body).name;
  switch (pair.kind) {
    case RobotPair::Kind::kBody:
      return {body, collision_bodies_.at(pair.other).name};
    case RobotPair::Kind::kObstacle:
      return {body, discs_.obstacles().at(pair.other).name};
    case RobotPair::Kind::kWall:
      return {body, discs_.walls().at(pair.other).name};
  }
  return {body, ""};
}

CentrePair RobotScene::centrePair(const RobotPair& pair) const {
  const CollisionBody& a = collision_bodies_.at(pair.body);
  CentrePair result;
  result.a = a.centre;
  const auto padded = [](const Eigen::VectorXd& v) {
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    p.head(v.size()) = v;
    return p;
  };
  switch (pair.kind) {
    case RobotPair::Kind::kBody: {
      const CollisionBody& b = collision_bodies_.at(pair.other);
      result.kind = CentrePair::Kind::kCentre;
      result.b = b.centre;
      result.constant = (a.radius + b.radius) * (a.radius + b.radius);
      break;
    }
    case RobotPair::Kind::kObstacle: {
      const SceneObstacle& o = discs_.obstacles().at(pair.other);
      result.kind = CentrePair::Kind::kPoint;
      result.point = padded(o.position);
      result.constant = (a.radius + o.radius) * (a.radius + o.radius);
      break;
    }
    case RobotPair::Kind::kWall: {
      const SceneWall& w = discs_.walls().at(pair.other);
      result.kind = CentrePair::Kind::kWall;
      result.point = padded(w.normal);
      result.constant = w.offset + a.radius;
      break;
    }
  }
  return result;
}

double RobotScene::constraintValue(const RobotPair& pair, const Eigen::VectorXd& x) const {
  CentreEvaluator evaluator(robot_, dimension());
  evaluator.setState(x.data());
  return centrePairValue(evaluator, centrePair(pair));
}

double RobotScene::pairGap(const RobotPair& pair, const Eigen::VectorXd& x) const {
  return pairGaps({pair}, x)[0];
}

std::vector<double> RobotScene::pairGaps(const std::vector<RobotPair>& pairs,
                                         const Eigen::VectorXd& x) const {
  CentreEvaluator evaluator(robot_, dimension());
  evaluator.setState(x.data());  // one forward kinematics for all pairs
  std::vector<double> gaps;
  gaps.reserve(pairs.size());
  for (const RobotPair& pair : pairs) {
    const double c = centrePairValue(evaluator, centrePair(pair));
    if (pair.kind == RobotPair::Kind::kWall) {
      gaps.push_back(c);
      continue;
    }
    const double radii =
        collision_bodies_[pair.body].radius + (pair.kind == RobotPair::Kind::kBody
                                                   ? collision_bodies_[pair.other].radius
                                                   : discs_.obstacles()[pair.other].radius);
    gaps.push_back(std::sqrt(std::max(0.0, c + radii * radii)) - radii);
  }
  return gaps;
}

std::shared_ptr<const DcsModel> RobotScene::model(const std::vector<RobotPair>& pairs) const {
  CentrePairSystem system;
  system.robot = robot_;
  system.dimension = dimension();
  system.state_size = stateSize();
  system.control_size = controlSize();
  for (int j = 0; j < numJoints(); ++j) system.actuation.emplace_back(j, j);
  for (int b = 0; b < static_cast<int>(discs_.bodies().size()); ++b) {
    if (!discs_.bodies()[b].actuated) continue;
    for (int d = 0; d < dimension(); ++d) {
      system.actuation.emplace_back(bodyStateIndex(b) + d,
                                    numJoints() + discs_.controlIndex(b) + d);
    }
  }
  system.constraint_scales.resize(pairs.size());
  for (size_t k = 0; k < pairs.size(); ++k) {
    system.pairs.push_back(centrePair(pairs[k]));
    // |grad_p c| on the boundary, as for discs; in q it is that times the lever arm, which
    // depends on the configuration.
    const CentrePair& c = system.pairs.back();
    system.constraint_scales(k) =
        c.kind == CentrePair::Kind::kWall ? 1.0 : 2.0 * std::sqrt(c.constant);
  }
  return centrePairModel(system, "robot_scene");
}

}  // namespace fesd
