#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/integrator/fesd_integrator.h"
#include "fesd_trajopt/planning/scene_solver.h"
#include "fesd_trajopt/scene/scene_task.h"

namespace fesd {

/// How a plan is executed with feedback (executeWithFeedback).
struct ClosedLoopOptions {
  /// Control intervals executed between two replans.
  int replan_every = 3;
  /// The first plan: the node's default request (verified, the accuracy ladder).
  SceneSolveOptions first;
  double first_accuracy = 1e-2;  ///< relative to the length scale (solveToAccuracy)
  /// The first plan when it is already solved (with these options); not owned.
  const SceneOutcome* first_plan = nullptr;
  /// Each replan: the fastest answer (unverified), warm from the rest of the plan before.
  SceneSolveOptions replan;
  /// The plant the controls are applied to: a fine FESD simulation of the scene.
  SimulationOptions plant;
};

/// One replan of a closed loop.
struct Replan {
  int after_intervals = 0;  ///< the intervals executed before it
  SolveStatus status = SolveStatus::kSolverError;
  double seconds = 0.0;
  int iterations = 0;
  bool warm_started = false;
  int pair_rounds = 0;
  std::vector<HomotopyStep> history;  ///< its relaxed and polishing NLPs, all rounds
  std::string message;                ///< the answer's, or why the request was refused
};

struct ClosedLoopRun {
  SolveStatus status = SolveStatus::kSolverError;  ///< kSuccess when the loop ran to the end
  std::string message;
  SceneOutcome first;  ///< the first plan
  double first_seconds = 0.0;
  std::vector<Replan> replans;
  double replan_seconds = 0.0;  ///< all replans together
  Trajectory executed;          ///< the plant's motion, of the full scene
  Eigen::VectorXd end;          ///< the plant's state at the horizon
};

/// Executes a task's plan with feedback: the first plan's controls drive the plant (a simulation
/// of the scene standing in for the robot) for replan_every intervals, then a new plan over the
/// rest of the horizon starts from the state reached, warm from the rest of the plan before
/// (SceneSolveOptions::previous: the intervals still to come), and so on to the horizon. Open
/// loop, a push by one pusher amplifies the plan's error many times over; closed like this it
/// ends where the plan meant to. The task's horizon must hold whole intervals.
ClosedLoopRun executeWithFeedback(const SceneTask& task, const TaskLimits& limits,
                                  const ClosedLoopOptions& options);

}  // namespace fesd
