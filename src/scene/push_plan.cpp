#include "fesd_trajopt/scene/push_plan.h"

#include <algorithm>
#include <cmath>
#include <memory>

namespace fesd {
namespace {

constexpr double kDegree = M_PI / 180.0;

bool insideWorkspace(const BodyTask& task, const Eigen::VectorXd& p) {
  for (int d = 0; d < p.size(); ++d) {
    if (task.workspace_lower.size() && p(d) < task.workspace_lower(d)) return false;
    if (task.workspace_upper.size() && p(d) > task.workspace_upper(d)) return false;
  }
  return true;
}

Eigen::VectorXd clampToWorkspace(const BodyTask& task, Eigen::VectorXd p) {
  if (task.workspace_lower.size()) p = p.cwiseMax(task.workspace_lower);
  if (task.workspace_upper.size()) p = p.cwiseMin(task.workspace_upper);
  return p;
}

/// Unit vectors from a pushed body towards candidate pusher poses: straight behind the push
/// first, then tilted away from it in steps of 1 degree (in 2-D to either side, in 3-D towards
/// 12 directions around it).
std::vector<Eigen::VectorXd> candidateDirections(const Eigen::VectorXd& push_direction) {
  const Eigen::VectorXd behind = -push_direction;
  std::vector<Eigen::VectorXd> sideways;
  if (behind.size() == 2) {
    const Eigen::Vector2d normal(-behind(1), behind(0));
    sideways = {normal, -normal};
  } else {
    int axis;
    behind.cwiseAbs().minCoeff(&axis);
    const Eigen::Vector3d b = behind;
    const Eigen::Vector3d e1 = (Eigen::Vector3d::Unit(axis) - b(axis) * b).normalized();
    const Eigen::Vector3d e2 = b.cross(e1);
    for (int k = 0; k < 12; ++k) {
      sideways.push_back(std::cos(30.0 * k * kDegree) * e1 + std::sin(30.0 * k * kDegree) * e2);
    }
  }
  std::vector<Eigen::VectorXd> candidates{behind};
  for (int degrees = 1; degrees < 90; ++degrees) {
    for (const Eigen::VectorXd& side : sideways) {
      candidates.push_back(std::cos(degrees * kDegree) * behind +
                           std::sin(degrees * kDegree) * side);
    }
  }
  return candidates;
}

/// Straight from a to b as s goes from 0 to 1 (clamped).
Eigen::VectorXd along(const Eigen::VectorXd& a, const Eigen::VectorXd& b, double s) {
  return a + std::min(1.0, std::max(0.0, s)) * (b - a);
}

/// lambda >= 0 minimising |G lambda - v| (active set: drop the most negative and solve again).
Eigen::VectorXd nonnegativeLeastSquares(const Eigen::MatrixXd& G, const Eigen::VectorXd& v) {
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(G.cols());
  std::vector<int> free(G.cols());
  for (int j = 0; j < G.cols(); ++j) free[j] = j;
  while (!free.empty()) {
    Eigen::MatrixXd columns(G.rows(), free.size());
    for (size_t k = 0; k < free.size(); ++k) columns.col(k) = G.col(free[k]);
    const Eigen::VectorXd solution = columns.colPivHouseholderQr().solve(v);
    int most_negative;
    if (solution.minCoeff(&most_negative) >= 0.0) {
      for (size_t k = 0; k < free.size(); ++k) lambda(free[k]) = solution(k);
      break;
    }
    free.erase(free.begin() + most_negative);
  }
  return lambda;
}

/// The planned positions of every body as functions of time.
class PlannedMotion {
 public:
  PlannedMotion(const SceneTask& task, const std::vector<PushAssignment>& pushes,
                double contact_time, double release_time)
      : task_(task), pushes_(pushes), contact_(contact_time), release_(release_time) {}

  Eigen::VectorXd state(double t) const {
    const DiscScene& scene = task_.scene;
    const int dim = scene.dimension(), count = static_cast<int>(scene.bodies().size());
    Eigen::VectorXd x(scene.stateSize());
    for (int b = 0; b < count; ++b) x.segment(scene.stateIndex(b), dim) = plannedPosition(b, t);
    // Actuated bodies step out of what they would pass through, in a fixed order.
    for (int b = 0; b < count; ++b) {
      if (!scene.bodies()[b].actuated) continue;
      Eigen::VectorXd p = x.segment(scene.stateIndex(b), dim);
      const double radius = scene.bodies()[b].radius;
      for (const SceneObstacle& obstacle : scene.obstacles()) {
        p = outside(p, obstacle.position, radius + obstacle.radius);
      }
      for (int other = 0; other < count; ++other) {
        if (scene.bodies()[other].actuated || pushing(b, other, t)) continue;
        p = outside(p, x.segment(scene.stateIndex(other), dim),
                    radius + scene.bodies()[other].radius);
      }
      for (const SceneWall& wall : scene.walls()) {
        const double gap = wall.normal.dot(p) - wall.offset - radius;
        if (gap < 0.0) p -= gap * wall.normal;
      }
      x.segment(scene.stateIndex(b), dim) = clampToWorkspace(task_.bodies[b], p);
    }
    return x;
  }

 private:
  const PushAssignment* pushOf(int body) const {
    for (const PushAssignment& push : pushes_) {
      if (push.pusher == body) return &push;
    }
    return nullptr;
  }
  bool isPushed(int body) const {
    return std::any_of(pushes_.begin(), pushes_.end(),
                       [body](const PushAssignment& p) { return p.pushed == body; });
  }
  bool pushing(int pusher, int pushed, double t) const {
    const PushAssignment* push = pushOf(pusher);
    return push && push->pushed == pushed && t > contact_ && t <= release_;
  }
  Eigen::VectorXd start(int body) const { return task_.scene.bodies()[body].position; }
  /// The task's target, or the start when the body has none.
  Eigen::VectorXd goal(int body, const Eigen::VectorXd& otherwise) const {
    const BodyTask& t = task_.bodies[body];
    return t.target.size() && t.target_weight > 0.0 ? t.target : otherwise;
  }
  Eigen::VectorXd plannedPosition(int body, double t) const {
    const double horizon = task_.horizon;
    if (isPushed(body)) {
      return along(start(body), goal(body, start(body)),
                   (t - contact_) / std::max(release_ - contact_, 1e-300));
    }
    const PushAssignment* push = pushOf(body);
    if (!push) return along(start(body), goal(body, start(body)), t / horizon);
    const Eigen::VectorXd pushed_start = start(push->pushed);
    const Eigen::VectorXd pushed_goal = goal(push->pushed, pushed_start);
    if (t <= contact_) {
      return along(start(body), pushed_start + push->offset, t / std::max(contact_, 1e-300));
    }
    if (t <= release_) return plannedPosition(push->pushed, t) + push->offset;
    const Eigen::VectorXd released = pushed_goal + push->offset;
    return along(released, goal(body, released),
                 (t - release_) / std::max(horizon - release_, 1e-300));
  }
  /// p moved radially out of the ball (centre, distance), or p itself.
  static Eigen::VectorXd outside(const Eigen::VectorXd& p, const Eigen::VectorXd& centre,
                                 double distance) {
    const Eigen::VectorXd away = p - centre;
    const double length = away.norm();
    if (length >= distance) return p;
    // A path through the very centre leaves along the first axis (a fixed, deterministic choice).
    const Eigen::VectorXd direction =
        length > 0.0 ? Eigen::VectorXd(away / length) : Eigen::VectorXd::Unit(p.size(), 0);
    return centre + distance * direction;
  }

  SceneTask task_;
  std::vector<PushAssignment> pushes_;
  double contact_, release_;
};

int bodyPairIndex(const std::vector<ContactPair>& modelled, int a, int b) {
  for (size_t k = 0; k < modelled.size(); ++k) {
    const ContactPair& pair = modelled[k];
    if (pair.kind != ContactPair::Kind::kBody) continue;
    if ((pair.body == a && pair.other == b) || (pair.body == b && pair.other == a)) return k;
  }
  return -1;
}

/// The pushers of one passive body, placed in index order.
std::vector<PushAssignment> placePushers(const SceneTask& task,
                                         const std::vector<ContactPair>& modelled, int pushed,
                                         std::vector<bool>& busy) {
  const DiscScene& scene = task.scene;
  const Eigen::VectorXd start = scene.bodies()[pushed].position;
  const Eigen::VectorXd target = task.bodies[pushed].target;
  const std::vector<Eigen::VectorXd> candidates =
      candidateDirections((target - start).normalized());
  std::vector<PushAssignment> placed;
  for (int pusher = 0; pusher < static_cast<int>(scene.bodies().size()); ++pusher) {
    if (!scene.bodies()[pusher].actuated || busy[pusher] ||
        bodyPairIndex(modelled, pusher, pushed) < 0) {
      continue;
    }
    const double radius = scene.bodies()[pusher].radius;
    const double distance = radius + scene.bodies()[pushed].radius;
    for (const Eigen::VectorXd& direction : candidates) {
      const Eigen::VectorXd offset = distance * direction;
      const bool fits =
          insideWorkspace(task.bodies[pusher], start + offset) &&
          insideWorkspace(task.bodies[pusher], target + offset) &&
          std::all_of(placed.begin(), placed.end(), [&](const PushAssignment& p) {
            return (p.offset - offset).norm() >= radius + scene.bodies()[p.pusher].radius;
          });
      if (!fits) continue;
      placed.push_back({pusher, pushed, offset});
      busy[pusher] = true;
      break;
    }
  }
  return placed;
}

}  // namespace

PushPlan planPushes(const SceneTask& task, const std::vector<ContactPair>& modelled) {
  const DiscScene& scene = task.scene;
  const int count = static_cast<int>(scene.bodies().size()), dim = scene.dimension();
  PushPlan plan;
  std::vector<bool> busy(count, false);
  for (int b = 0; b < count; ++b) {
    const BodyTask& t = task.bodies[b];
    if (scene.bodies()[b].actuated || !t.target.size() || !(t.target_weight > 0.0) ||
        (t.target - scene.bodies()[b].position).norm() == 0.0) {
      continue;
    }
    const std::vector<PushAssignment> pushers = placePushers(task, modelled, b, busy);
    plan.pushes.insert(plan.pushes.end(), pushers.begin(), pushers.end());
  }

  // The impulse (lambda times the push's duration) of each pushing pair: G impulse = the pushed
  // body's displacement, with G's columns grad_{p_pushed} c = 2 (p_pushed - p_pusher) = -2 offset.
  Eigen::VectorXd impulse = Eigen::VectorXd::Zero(modelled.size());
  for (int b = 0; b < count; ++b) {
    std::vector<const PushAssignment*> own;
    for (const PushAssignment& p : plan.pushes) {
      if (p.pushed == b) own.push_back(&p);
    }
    if (own.empty()) continue;
    Eigen::MatrixXd G(dim, own.size());
    for (size_t k = 0; k < own.size(); ++k) G.col(k) = -2.0 * own[k]->offset;
    const Eigen::VectorXd lambda =
        nonnegativeLeastSquares(G, task.bodies[b].target - scene.bodies()[b].position);
    for (size_t k = 0; k < own.size(); ++k) {
      impulse(bodyPairIndex(modelled, own[k]->pusher, b)) = lambda(k);
    }
  }
  // Phase lengths of least control effort: with straight, uniform motion a phase of length tau
  // costs c / tau, c = the sum of the pushers' squared (control x tau), so tau ~ sqrt(c). In the
  // push a pusher's control is its velocity minus the reaction 2 offset lambda.
  double approach = 0.0, push = 0.0, back = 0.0;
  for (const PushAssignment& p : plan.pushes) {
    const Eigen::VectorXd start = scene.bodies()[p.pushed].position;
    const Eigen::VectorXd target = task.bodies[p.pushed].target;
    const BodyTask& pusher = task.bodies[p.pusher];
    approach += (start + p.offset - scene.bodies()[p.pusher].position).squaredNorm();
    push += (target - start - 2.0 * p.offset * impulse(bodyPairIndex(modelled, p.pusher, p.pushed)))
                .squaredNorm();
    if (pusher.target.size() && pusher.target_weight > 0.0) {
      back += (pusher.target - target - p.offset).squaredNorm();
    }
  }
  const double total = std::sqrt(approach) + std::sqrt(push) + std::sqrt(back);
  plan.contact_time = plan.release_time = task.horizon;
  if (!plan.pushes.empty() && total > 0.0) {
    plan.contact_time = task.horizon * std::sqrt(approach) / total;
    plan.release_time = task.horizon * (std::sqrt(approach) + std::sqrt(push)) / total;
  }
  const auto motion =
      std::make_shared<PlannedMotion>(task, plan.pushes, plan.contact_time, plan.release_time);
  plan.guess.state = [motion](double t) { return motion->state(t); };
  const double contact = plan.contact_time, release = plan.release_time;
  const Eigen::VectorXd push_lambda = release > contact
                                          ? Eigen::VectorXd(impulse / (release - contact))
                                          : Eigen::VectorXd(Eigen::VectorXd::Zero(impulse.size()));
  plan.guess.multipliers = [push_lambda, contact, release](double t) {
    return t > contact && t <= release ? push_lambda
                                       : Eigen::VectorXd(Eigen::VectorXd::Zero(push_lambda.size()));
  };

  // Controls: the mean planned velocity over each interval minus the mean contact reaction
  // grad_{p_pusher} c lambda = 2 offset lambda.
  for (int k = 0; k < task.num_intervals; ++k) {
    const double begin = task.horizon * k / task.num_intervals;
    const double end = task.horizon * (k + 1) / task.num_intervals;
    const Eigen::VectorXd velocity = (motion->state(end) - motion->state(begin)) / (end - begin);
    const double pushing_share =
        std::max(0.0, std::min(end, release) - std::max(begin, contact)) / (end - begin);
    Eigen::VectorXd u = Eigen::VectorXd::Zero(scene.controlSize());
    for (int b = 0; b < count; ++b) {
      if (scene.bodies()[b].actuated) {
        u.segment(scene.controlIndex(b), dim) = velocity.segment(scene.stateIndex(b), dim);
      }
    }
    for (const PushAssignment& p : plan.pushes) {
      u.segment(scene.controlIndex(p.pusher), dim) -=
          2.0 * p.offset * push_lambda(bodyPairIndex(modelled, p.pusher, p.pushed)) * pushing_share;
    }
    plan.guess.controls.push_back(u);
  }
  return plan;
}

}  // namespace fesd
