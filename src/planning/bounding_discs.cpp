#include "fesd_trajopt/planning/bounding_discs.h"

#include <algorithm>
#include <limits>

#include <Eigen/Geometry>

namespace fesd {

bool hasCompositeBodies(const Scene& scene) {
  if (scene.hasRobot()) return false;
  return std::any_of(scene.bodies().begin(), scene.bodies().end(),
                     [](const SceneBody& body) { return !body.spheres.empty() || body.turns; });
}

namespace {

/// How much nearer than its bounding disc a body of spheres gets to a wall of normal n at yaw:
/// the disc's radius minus max_k (r_k - n . R(yaw) o_k).
double wallSlack(const SceneBody& body, double radius, const Eigen::VectorXd& normal, double yaw) {
  double support = -std::numeric_limits<double>::infinity();
  for (const FreeBodySphere& sphere : body.spheres) {
    const Eigen::Vector2d turned = Eigen::Rotation2Dd(yaw) * sphere.offset.head<2>();
    support = std::max(support, sphere.radius - normal.head<2>().dot(turned));
  }
  return radius - support;
}

}  // namespace

SceneBody boundingDisc(SceneBody body) {
  body.radius = boundingRadius(body);
  body.spheres.clear();
  body.turns = false;
  body.yaw = body.turning_radius = 0.0;
  return body;
}

SceneTask boundingDiscTask(const SceneTask& task) {
  SceneTask discs = task;
  // A wall moves back by the most any body of spheres gets nearer to it than its disc at the yaw
  // it is to end with: a box is pushed into a corner its disc would not fit (the pushers' guess
  // may then come as much nearer to the wall).
  for (SceneWall& wall : discs.scene.walls()) {
    double slack = 0.0;
    for (size_t b = 0; b < task.scene.bodies().size(); ++b) {
      const SceneBody& body = task.scene.bodies()[b];
      if (body.spheres.empty() || task.scene.dimension() != 2) continue;
      const double yaw = task.bodies[b].hasYawTarget() ? task.bodies[b].target_yaw : body.yaw;
      slack = std::max(slack, wallSlack(body, boundingRadius(body), wall.normal, yaw));
    }
    wall.offset -= slack;
  }
  for (size_t b = 0; b < discs.scene.bodies().size(); ++b) {
    discs.scene.bodies()[b] = boundingDisc(discs.scene.bodies()[b]);
    discs.bodies[b].target_yaw = discs.bodies[b].target_yaw_weight = 0.0;
  }
  discs.allowed_pairs.clear();
  return discs;
}

BoundingDiscPairs boundingDiscPairs(const Scene& scene, const std::vector<ContactPair>& pairs) {
  const std::vector<CollisionBody> bodies = scene.collisionBodies();
  BoundingDiscPairs discs;
  for (const ContactPair& pair : pairs) {
    ContactPair disc = pair;
    disc.body = bodies.at(pair.body).free_body;
    if (pair.kind == ContactPair::Kind::kBody) disc.other = bodies.at(pair.other).free_body;
    const auto found = std::find(discs.pairs.begin(), discs.pairs.end(), disc);
    discs.disc_of.push_back(static_cast<int>(found - discs.pairs.begin()));
    if (found == discs.pairs.end()) discs.pairs.push_back(disc);
  }
  return discs;
}

TrajectoryGuess guessOfSpheres(const SceneTask& task, const std::vector<ContactPair>& pairs,
                               const BoundingDiscPairs& discs, const TrajectoryGuess& disc_guess) {
  const std::vector<int> disc_of = discs.disc_of;
  const int disc_pair_count = static_cast<int>(discs.pairs.size());
  const Scene scene = task.scene;  // the guess outlives the caller's task (a proxy's)
  const int dim = scene.dimension();
  const Scene disc_scene = boundingDiscTask(task).scene;
  TrajectoryGuess guess;
  guess.controls = disc_guess.controls;
  guess.state = [=](double t) {
    const Eigen::VectorXd discs = disc_guess.state(t);
    Eigen::VectorXd x = scene.initialState();
    for (int b = 0; b < static_cast<int>(scene.bodies().size()); ++b) {
      x.segment(scene.stateIndex(b), dim) = discs.segment(disc_scene.stateIndex(b), dim);
    }
    return x;
  };
  if (!disc_guess.multipliers) return guess;
  const auto state = guess.state;
  guess.multipliers = [=](double t) {
    const Eigen::VectorXd disc_lambda = disc_guess.multipliers(t);
    const std::vector<double> gaps = scene.pairGaps(pairs, state(t));
    std::vector<int> nearest(disc_pair_count, -1);
    for (size_t k = 0; k < pairs.size(); ++k) {
      int& best = nearest[disc_of[k]];
      if (best < 0 || gaps[k] < gaps[best]) best = static_cast<int>(k);
    }
    Eigen::VectorXd lambda = Eigen::VectorXd::Zero(pairs.size());
    for (int j = 0; j < disc_pair_count; ++j) {
      if (nearest[j] >= 0) lambda(nearest[j]) = disc_lambda(j);
    }
    return lambda;
  };
  return guess;
}

}  // namespace fesd
