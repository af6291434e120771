#pragma once

#include <memory>
#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/planning/paths_around.h"
#include "fesd_trajopt/planning/push_plan.h"
#include "fesd_trajopt/scene/scene_task.h"

namespace fesd {

/// The motion of every body of a push plan as functions of time, and the forces that move them:
/// pushed bodies along their pushes (round the corners of a push in legs), actuated bodies along
/// their transits or behind the body they push (turning with it), the other passive bodies of
/// `pairs` shoved by what pushes into them as the projection would (simulated in steps in which
/// nothing moves farther than 5 % of the smallest radius). Actuated bodies shove the simulated
/// bodies they meet, step out of the other passive bodies they do not push, obstacles and walls,
/// and stay in their workspaces.
class PlannedMotion {
 public:
  PlannedMotion(const SceneTask& task, const std::vector<ContactPair>& pairs,
                const std::vector<PushLeg>& legs, const std::vector<Transit>& transits);

  Eigen::VectorXd state(double t) const;

  /// The forces of the pairs in contact at t (with a passive side) that move the passive bodies
  /// with their planned velocities, in the least-squares sense with lambda >= 0: first those of
  /// the simulated bodies, which they move exactly as the projection did, then those of the
  /// pushed bodies, which also carry the reactions of what they shove.
  Eigen::VectorXd multipliers(double t) const;

  /// The mean control of [begin, end]: the mean planned velocity of the actuated bodies minus
  /// the mean contact reaction on them (4 midpoints per piece between the plan's breaks).
  Eigen::VectorXd meanControl(double begin, double end) const;

 private:
  /// A stretch of one body's plan: a transit, a leg it is pushed along, or a leg it pushes in
  /// (behind the pushed body at `offset`).
  struct Piece {
    double begin, end;
    int transit = -1;        ///< index in transits_
    int leg = -1;            ///< index in legs_
    Eigen::VectorXd offset;  ///< for a pusher in `leg`; empty for the pushed body
  };

  Eigen::VectorXd plannedPosition(int body, double t) const;
  bool pushing(int pusher, int pushed, double t) const;
  void placePlannedBodies(double t, Eigen::VectorXd& x) const;
  void fitForces(const std::vector<int>& active, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                 Eigen::VectorXd& lambda, bool simulated_bodies) const;
  Eigen::VectorXd velocity(double t) const;
  /// Moves simulated body b out of everything its pairs name, as the projection would.
  void shove(int b, Eigen::VectorXd& x) const;
  void simulate();

  SceneTask task_;
  std::vector<ContactPair> pairs_;
  std::vector<PushLeg> legs_;
  std::vector<std::shared_ptr<const RoundedPath>> rounded_;  ///< per leg with turns, else null
  std::vector<Transit> transits_;
  std::vector<std::vector<Piece>> pieces_;  ///< per body, in order of time
  std::vector<double> breaks_;              ///< where any piece begins or ends, sorted
  std::vector<bool> simulated_;  ///< passive bodies without a goal: they move only when pushed
  double sample_step_ = 0.0;
  std::vector<Eigen::VectorXd> samples_;  ///< full states every sample_step_ (when simulating)
};

}  // namespace fesd
