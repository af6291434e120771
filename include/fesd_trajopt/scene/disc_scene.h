#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/model/dcs_model.h"

namespace fesd {

/// A moving disc (2-D) or sphere (3-D). Actuated bodies are velocity-controlled
/// (xdot = u); passive ones only move when pushed.
struct SceneBody {
  std::string name;
  double radius = 1.0;
  Eigen::VectorXd position;  ///< initial position
  bool actuated = false;
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

/// A contact the model enforces: body against another body, an obstacle or a wall.
struct ContactPair {
  enum class Kind { kBody, kObstacle, kWall };
  int body;
  Kind kind;
  int other;  ///< index into bodies, obstacles or walls

  bool operator==(const ContactPair& o) const {
    return body == o.body && kind == o.kind && other == o.other;
  }
};

/// Bodies, obstacles and walls in the plane or in space, as a projected dynamical system:
/// x stacks the body positions, u the actuated bodies' velocities, f(x, u) = B u, and every
/// chosen contact pair gives a constraint
///   body-body:      c = |p_i - p_j|^2 - (R_i + R_j)^2
///   body-obstacle:  c = |p_i - o|^2 - (R_i + R_o)^2
///   body-wall:      c = n . p_i - offset - R_i
/// with analytic, sparse derivatives (the pair constraints are quadratic, so the velocity's
/// Hessian is a constant pattern scaled by the weights).
class DiscScene {
 public:
  explicit DiscScene(int dimension) : dimension_(dimension) {}

  int dimension() const { return dimension_; }
  std::vector<SceneBody>& bodies() { return bodies_; }
  const std::vector<SceneBody>& bodies() const { return bodies_; }
  std::vector<SceneObstacle>& obstacles() { return obstacles_; }
  const std::vector<SceneObstacle>& obstacles() const { return obstacles_; }
  std::vector<SceneWall>& walls() { return walls_; }
  const std::vector<SceneWall>& walls() const { return walls_; }

  int stateSize() const { return dimension_ * static_cast<int>(bodies_.size()); }
  int controlSize() const;
  /// First state index of a body's position.
  int stateIndex(int body) const { return dimension_ * body; }
  /// A body's position at a state of the scene.
  Eigen::VectorXd position(int body, const Eigen::VectorXd& x) const {
    return x.segment(stateIndex(body), dimension_);
  }
  /// First control index of a body's velocity, or -1 for a passive body.
  int controlIndex(int body) const;
  Eigen::VectorXd initialState() const;
  /// Every pair that could touch: all body pairs, every body with every obstacle and wall.
  std::vector<ContactPair> allPairs() const;
  /// The constraint value of one pair at a state (> 0: apart).
  double constraintValue(const ContactPair& pair, const Eigen::VectorXd& x) const;
  std::string pairName(const ContactPair& pair) const;

  /// The DCS with the given contact pairs (they are the constraints, in that order).
  std::shared_ptr<const DcsModel> model(const std::vector<ContactPair>& pairs) const;

 private:
  int dimension_;
  std::vector<SceneBody> bodies_;
  std::vector<SceneObstacle> obstacles_;
  std::vector<SceneWall> walls_;
};

}  // namespace fesd
