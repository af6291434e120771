#include "trajopt_node.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <exception>
#include <optional>
#include <sstream>

#include "builtin_systems.h"
#include "fesd_trajopt/integrator/fesd_integrator.h"
#include "fesd_trajopt/planning/accuracy_ladder.h"
#include "fesd_trajopt/planning/closed_loop.h"
#include "fesd_trajopt/scene/scene_units.h"
#include "fesd_trajopt/solver/heap_policy.h"
#include "fesd_trajopt/solver/stopwatch.h"
#include "scene_request.h"
#include "sensitivity_message.h"
#include "solution_message.h"

namespace fesd_ros {
namespace {

constexpr double kPlaybackFramesPerSecond = 25.0;

/// The discretisation of a request: its values where given, else the configuration's.
struct Discretization {
  int elements, stages;
  std::string error;
};

template <class Request>
Discretization discretization(const Request& request, const NodeConfig& config) {
  Discretization d{
      request.has_num_elements ? static_cast<int>(request.num_elements) : config.num_elements,
      request.has_num_stages ? static_cast<int>(request.num_stages) : config.num_stages, ""};
  if (d.elements < 1 || d.elements > config.limits.max_elements) {
    d.error = "num_elements must be in 1.." + std::to_string(config.limits.max_elements) +
              ", got " + std::to_string(d.elements);
  } else if (d.stages < 1 || d.stages > config.limits.max_stages) {
    d.error = "num_stages must be in 1.." + std::to_string(config.limits.max_stages) + ", got " +
              std::to_string(d.stages);
  }
  return d;
}

/// The accuracy a plan request asks for, in units of the scene's length scale (as the ladder
/// takes it): its own (> 0, in the scene's units), the configured default (0, relative already),
/// or none (< 0, or a default of 0): then 0.
double targetAccuracy(const fesd_trajopt::PlanRequest& request, const NodeConfig& config,
                      double length_scale) {
  if (request.target_accuracy < 0.0) return 0.0;
  return request.target_accuracy > 0.0 ? request.target_accuracy / length_scale
                                       : config.target_accuracy;
}

/// The wall-time budget of a request: its own where given, else the configuration's.
template <class Request>
double wallTimeBudget(const Request& request, const NodeConfig& config) {
  return request.has_wall_time_budget ? request.wall_time_budget : config.wall_time_budget;
}

/// The discretisation, method, tolerance and budget of a plan request as solver options;
/// returns "" or why the request is refused.
std::string solveOptions(const fesd_trajopt::PlanRequest& request, const NodeConfig& config,
                         fesd::OcpOptions& options) {
  const Discretization grid = discretization(request, config);
  if (!grid.error.empty()) return grid.error;
  if (request.method > fesd_trajopt::PlanRequest::METHOD_STANDARD) {
    return "unknown method " + std::to_string(request.method);
  }
  const double tolerance = request.has_complementarity_tolerance ? request.complementarity_tolerance
                                                                 : config.complementarity_tolerance;
  const double budget = wallTimeBudget(request, config);
  if (!(tolerance > 0.0) || !std::isfinite(tolerance)) {
    return "the complementarity tolerance must be > 0 and finite";
  }
  if (!(budget > 0.0)) return "the wall-time budget must be > 0";
  if (!std::isfinite(request.target_accuracy)) return "the target accuracy must be finite";
  if (request.contact_pairs > fesd_trajopt::PlanRequest::PAIRS_ALL_IN_REACH) {
    return "unknown contact_pairs " + std::to_string(request.contact_pairs);
  }
  options.discretization.num_elements = grid.elements;
  options.discretization.num_stages = grid.stages;
  options.discretization.switch_detection =
      request.method == fesd_trajopt::PlanRequest::METHOD_DEFAULT
          ? config.fesd
          : request.method == fesd_trajopt::PlanRequest::METHOD_FESD;
  options.homotopy.complementarity_tolerance = tolerance;
  options.homotopy.wall_time_budget = budget;
  options.homotopy.ipopt.linear_solver = config.linear_solver;
  options.homotopy.method = config.mpcc_method;
  return "";
}

template <class Response>
void answerUnsolved(Response& response, uint8_t status, const std::string& message) {
  setUnsolved(response, status, message);
  ROS_WARN_STREAM("fesd_trajopt: " << message);
}

template <class Response>
void refuse(Response& response, const std::string& why) {
  answerUnsolved(response, kInvalidRequest, "invalid request: " + why);
}

/// A valid request that asks for the impossible.
template <class Response>
void answerInfeasible(Response& response, const std::string& why) {
  answerUnsolved(response, statusCode(fesd::SolveStatus::kInfeasible), "infeasible: " + why);
}

template <class Response>
void finish(Response& response, const std::vector<std::string>& notes) {
  response.status = response.solution.status;
  response.message = response.solution.message;
  for (const std::string& note : notes) response.message += "; " + note;
}

// Failures are answered with a status, never as a failed service call.
template <class Response, class Handler>
bool answerCatchingErrors(const char* service, Response& response, Handler handle) {
  try {
    handle();
  } catch (const std::exception& error) {
    response.status = statusCode(fesd::SolveStatus::kSolverError);
    response.message = std::string("internal error: ") + error.what();
    ROS_ERROR_STREAM("fesd_trajopt: " << service << ": " << response.message);
  }
  return true;
}

/// A link name as a graph resource name: other characters become '_', a leading digit gets a
/// 'b' before it (URDF allows names ROS topics do not).
std::string topicName(std::string name) {
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') c = '_';
  }
  if (name.empty() || std::isdigit(static_cast<unsigned char>(name[0]))) name = "b" + name;
  return name;
}

/// The request's body commands into the controls (per step); "" or why not.
std::string bodyCommands(const std::vector<fesd_trajopt::BodyTrajectory>& commands,
                         const fesd::Scene& scene, std::vector<Eigen::VectorXd>& controls) {
  const int dim = scene.dimension(), steps = static_cast<int>(controls.size());
  for (const fesd_trajopt::BodyTrajectory& command : commands) {
    int b = -1;
    for (size_t i = 0; i < scene.bodies().size(); ++i) {
      if (scene.bodies()[i].name == command.name) b = static_cast<int>(i);
    }
    if (b < 0 || !scene.bodies()[b].actuated) {
      return "a command names '" + command.name + "', not an actuated body";
    }
    if (command.controls.size() != 1 && static_cast<int>(command.controls.size()) != steps) {
      return "the command of '" + command.name + "' needs 1 or " + std::to_string(steps) +
             " controls";
    }
    for (int k = 0; k < steps; ++k) {
      const geometry_msgs::Vector3& v = command.controls[command.controls.size() == 1 ? 0 : k];
      Eigen::VectorXd u(dim);
      u(0) = v.x;
      u(1) = v.y;
      if (dim == 3) u(2) = v.z;
      if (!u.allFinite()) return "the command of '" + command.name + "' is not finite";
      controls[k].segment(scene.controlIndex(b), dim) = u;
    }
  }
  return "";
}

/// The request's joint commands (velocities, one point for all steps or one per step) into the
/// controls; "" or why not.
std::string jointCommands(const trajectory_msgs::JointTrajectory& commands,
                          const fesd::Scene& scene, std::vector<Eigen::VectorXd>& controls) {
  if (commands.joint_names.empty()) return "";
  if (!scene.hasRobot()) return "joint_commands are given, but the scene has no robot";
  const int steps = static_cast<int>(controls.size());
  if (commands.points.size() != 1 && static_cast<int>(commands.points.size()) != steps) {
    return "joint_commands needs 1 or " + std::to_string(steps) + " points, got " +
           std::to_string(commands.points.size());
  }
  for (size_t i = 0; i < commands.joint_names.size(); ++i) {
    const int j = scene.robot().jointIndex(commands.joint_names[i]);
    if (j < 0) {
      return "joint_commands names '" + commands.joint_names[i] +
             "', not a moving joint of the robot";
    }
    for (int k = 0; k < steps; ++k) {
      const auto& point = commands.points[commands.points.size() == 1 ? 0 : k];
      if (point.velocities.size() != commands.joint_names.size()) {
        return "each point of joint_commands needs one velocity per joint name";
      }
      if (!std::isfinite(point.velocities[i])) {
        return "the command of joint '" + commands.joint_names[i] + "' is not finite";
      }
      controls[k](j) = point.velocities[i];
    }
  }
  return "";
}

/// Why the sensitivities a request asks for are too many numbers to answer, or "".
std::string sensitivitiesTooLarge(const fesd_trajopt::Simulate::Request& request, int state_size,
                                  int control_size, int steps, double limit) {
  const double entries = sensitivityEntries(state_size, control_size, steps);
  if (!request.sensitivities || entries <= limit) return "";
  return "the sensitivities of " + std::to_string(steps) + " steps of " +
         std::to_string(state_size) + " states and " + std::to_string(control_size) +
         " controls take " + std::to_string(static_cast<long long>(entries)) +
         " numbers, more than ~limits/max_sensitivity_entries (" +
         std::to_string(static_cast<long long>(limit)) + "): ask for fewer steps";
}

}  // namespace

TrajoptNode::TrajoptNode(ros::NodeHandle node, ros::NodeHandle private_node)
    : node_(node),
      private_node_(private_node),
      config_(loadNodeConfig(private_node)),
      slots_(config_.solver_threads),
      playback_(private_node, config_.playback_rate, kPlaybackFramesPerSecond),
      plan_server_(
          private_node, config_.solver_threads,
          [this](const fesd_trajopt::PlanRequest& request, const fesd::SolveMonitor& monitor,
                 fesd_trajopt::PlanTrajectoryResult& answer) {
            plan(request, &monitor, answer);
            if (answer.status != kInvalidRequest) showTargets(request);
          }) {
  marker_publisher_ = private_node_.advertise<visualization_msgs::MarkerArray>("markers", 1, true);
  solution_publisher_ = private_node_.advertise<fesd_trajopt::Solution>("solution", 1, true);
  // rviz needs its fixed frame in TF: an identity transform to a child frame of this node.
  geometry_msgs::TransformStamped frame;
  frame.header.stamp = ros::Time::now();
  frame.header.frame_id = config_.frame_id;
  frame.child_frame_id = config_.frame_id + "_fesd_trajopt";
  frame.transform.rotation.w = 1.0;
  frame_broadcaster_.sendTransform(frame);
  solve_service_ =
      private_node_.advertiseService("solve_trajectory", &TrajoptNode::solveTrajectory, this);
  simulate_service_ = private_node_.advertiseService("simulate", &TrajoptNode::simulate, this);
  if (config_.interactive_targets) {
    targets_ = std::make_unique<InteractiveTargets>(
        private_node_, config_.frame_id,
        [this](const fesd_trajopt::PlanRequest& request, InteractiveTargets::Action action,
               const fesd::SolveMonitor& monitor) { solveTargets(request, action, monitor); });
    if (!config_.scene_urdf.empty()) showTargets(fesd_trajopt::PlanRequest());
  }
  plan_server_.start();
  ROS_INFO_STREAM("fesd_trajopt: ready ("
                  << config_.bodies.size() << " configured bodies, "
                  << (config_.scene_urdf.empty() ? "no default scene" : "default scene loaded")
                  << ")");
}

bool TrajoptNode::solveTrajectory(fesd_trajopt::SolveTrajectory::Request& request,
                                  fesd_trajopt::SolveTrajectory::Response& response) {
  fesd_trajopt::PlanTrajectoryResult answer;
  plan(request.request, nullptr, answer);
  if (answer.status != kInvalidRequest) showTargets(request.request);
  response.status = answer.status;
  response.message = answer.message;
  response.solution = answer.solution;
  return true;
}

bool TrajoptNode::simulate(fesd_trajopt::Simulate::Request& request,
                           fesd_trajopt::Simulate::Response& response) {
  const SolveSlots::Slot slot(slots_);
  answerCatchingErrors("simulate", response, [&] { handleSimulate(request, response); });
  fesd::releaseFreeMemory();
  return true;
}

void TrajoptNode::plan(const fesd_trajopt::PlanRequest& request, const fesd::SolveMonitor* monitor,
                       fesd_trajopt::PlanTrajectoryResult& answer,
                       std::shared_ptr<const fesd::SceneOutcome>* solved) {
  const SolveSlots::Slot slot(slots_);
  answerCatchingErrors("plan", answer, [&] { handlePlan(request, monitor, answer, solved); });
  fesd::releaseFreeMemory();  // the heap keeps what the solve freed until trimmed
}

TaskBuild TrajoptNode::planTask(const fesd_trajopt::PlanRequest& request) const {
  TaskBuild build =
      buildTask(config_, sceneFields(request),
                {request.joints, request.self_collision != 0, request.srdf_param}, private_node_);
  if (request.has_horizon) build.task.horizon = request.horizon;
  if (request.has_num_intervals) {
    build.task.num_intervals = static_cast<int>(request.num_intervals);
  }
  return build;
}

std::string TrajoptNode::planOptions(const fesd_trajopt::PlanRequest& request, bool robot,
                                     const fesd::SolveMonitor* monitor,
                                     fesd::SceneSolveOptions& options) const {
  const std::string problem = solveOptions(request, config_, options.ocp);
  if (!problem.empty()) return problem;
  const bool by_default = request.contact_pairs == fesd_trajopt::PlanRequest::PAIRS_DEFAULT;
  options.lazy_pairs = by_default ? config_.lazy_pairs
                                  : request.contact_pairs == fesd_trajopt::PlanRequest::PAIRS_LAZY;
  options.all_pairs_up_to = robot && by_default ? config_.robot_all_pairs_up_to : 0;
  options.pair_margin = config_.contact_margin;
  options.verify = request.verify;
  options.verification.num_stages = config_.verification_stages;
  options.verification.num_elements = config_.verification_elements;
  options.monitor = monitor;
  return "";
}

void TrajoptNode::handlePlan(const fesd_trajopt::PlanRequest& request,
                             const fesd::SolveMonitor* monitor,
                             fesd_trajopt::PlanTrajectoryResult& answer,
                             std::shared_ptr<const fesd::SceneOutcome>* solved) {
  fesd::Stopwatch stopwatch;
  TaskBuild build = planTask(request);
  if (!build.error.empty()) return refuse(answer, build.error);
  fesd::SceneTask& task = build.task;
  const bool robot = task.scene.hasRobot();
  fesd::SceneSolveOptions options;
  const std::string problem = planOptions(request, robot, monitor, options);
  if (!problem.empty()) return refuse(answer, problem);
  std::shared_ptr<const fesd::SceneOutcome> previous;
  if (request.warm_start) {
    std::lock_guard<std::mutex> lock(last_solution_mutex_);
    previous = last_solution_;
  }
  options.previous = previous.get();
  if (previous && fesd::solvedItsNlp(previous->status) && !request.has_num_elements &&
      !request.has_num_stages) {
    // A replan starts on the grid the last plan needed (of its intervals still to come).
    fesd::startOnPreviousRung(previous->structure, task.num_intervals, task.horizon,
                              options.ocp.discretization);
  }
  const double length_scale = fesd::lengthScale(task);
  const double accuracy = targetAccuracy(request, config_, length_scale);
  const fesd::SceneOutcome outcome =
      accuracy > 0.0 ? fesd::solveToAccuracy(task, config_.limits, options, accuracy)
                     : fesd::solveSceneTask(task, config_.limits, options);
  if (!outcome.invalid.empty()) return refuse(answer, outcome.invalid);
  if (!outcome.infeasible.empty()) return answerInfeasible(answer, outcome.infeasible);
  ROS_INFO_STREAM("fesd_trajopt: solved "
                  << (robot
                          ? "a robot of " + std::to_string(task.scene.numJoints()) +
                                " joints and " + std::to_string(task.scene.robot().spheres.size()) +
                                " spheres with "
                          : std::string())
                  << outcome.moving_bodies.size() << " moving of " << task.scene.bodies().size()
                  << " bodies, " << outcome.modelledPairs() << " modelled / "
                  << outcome.checkedPairs() << " checked / "
                  << outcome.decisions.size() - outcome.modelledPairs() - outcome.checkedPairs()
                  << " pruned pairs in " << outcome.pair_rounds << " round(s), "
                  << task.num_intervals << " intervals x " << outcome.structure.largestElements()
                  << " elements, n_s = " << outcome.structure.stages);
  fesd_trajopt::Solution& solution = answer.solution;
  solution = sceneSolution(task, outcome, build.planar_joints);
  solution.status = statusCode(outcome.status);
  solution.message = outcome.message;  // with the warning on unresolved switches
  solution.statistics.start =
      fesd::startName(outcome.start, robot ? "robot guess" : "push plan", outcome.plan_source);
  solution.statistics.pair_rounds = outcome.pair_rounds;
  solution.statistics.mpcc_method = fesd::methodName(config_.mpcc_method);
  solution.statistics.warm_started = outcome.warm_started;
  solution.statistics.nlp_variables = outcome.sizes.variables;
  solution.statistics.nlp_constraints = outcome.sizes.constraints;
  solution.statistics.complementarity_constraints = outcome.sizes.complementarities;
  fillAccuracy(task.scene, outcome, accuracy * length_scale, solution);
  if (solution.needs_feedback) {
    std::ostringstream feedback;
    feedback.precision(3);
    feedback << "; executed open loop the plan ends " << solution.open_loop_error
             << " from its planned end (";
    if (std::isfinite(solution.open_loop_gain)) {
      feedback << "a deviation grows up to " << solution.open_loop_gain << "-fold by the end";
    } else {
      const std::string& why = outcome.verification.gain_note;
      feedback << "no growth of a deviation to tell: "
               << (why.empty() ? "the sensitivities are undefined" : why);
    }
    feedback << "): execute it with feedback, replanning from the measured state with "
                "warm_start";
    solution.message += feedback.str();
  }
  solution.header.stamp = ros::Time::now();
  solution.header.frame_id = config_.frame_id;
  solution.statistics.wall_time = stopwatch.wallSeconds();
  solution.statistics.cpu_time = stopwatch.cpuSeconds();
  if (request.warm_start && !solution.statistics.warm_started) {
    build.notes.push_back("cold start: " + (previous ? outcome.cold_start_reason
                                                     : std::string("no previous solution")));
  }
  finish(answer, build.notes);
  ROS_INFO_STREAM("fesd_trajopt: " << answer.message << " (" << stopwatch.wallSeconds() << " s)");
  if (fesd::solvedItsNlp(outcome.status)) {  // a solution of its NLP: it can warm-start
    auto kept = std::make_shared<const fesd::SceneOutcome>(outcome);
    if (solved != nullptr) *solved = kept;
    std::lock_guard<std::mutex> lock(last_solution_mutex_);
    last_solution_ = kept;
  }
  publish(task, solution, outcome.planned_legs, outcome.planned_transits);
}

void TrajoptNode::showTargets(const fesd_trajopt::PlanRequest& request) {
  if (!targets_) return;
  const TaskBuild build = planTask(request);
  if (build.error.empty()) targets_->show(request, build.task);
}

void TrajoptNode::solveTargets(const fesd_trajopt::PlanRequest& request,
                               InteractiveTargets::Action action,
                               const fesd::SolveMonitor& monitor) {
  fesd_trajopt::PlanTrajectoryResult answer;
  std::shared_ptr<const fesd::SceneOutcome> solved;
  plan(request, &monitor, answer, &solved);
  if (action != InteractiveTargets::Action::kExecuteWithFeedback) return;
  if (!solved) {
    ROS_WARN_STREAM("fesd_trajopt: ~targets: no plan to execute: " << answer.message);
    return;
  }
  const SolveSlots::Slot slot(slots_);
  fesd_trajopt::PlanTrajectoryResult execution;
  answerCatchingErrors("execute with feedback", execution,
                       [&] { executeWithFeedback(request, *solved, monitor); });
  fesd::releaseFreeMemory();
}

void TrajoptNode::executeWithFeedback(const fesd_trajopt::PlanRequest& request,
                                      const fesd::SceneOutcome& plan,
                                      const fesd::SolveMonitor& monitor) {
  fesd::Stopwatch stopwatch;
  const TaskBuild build = planTask(request);  // it built for the plan
  const fesd::SceneTask& task = build.task;
  fesd::ClosedLoopOptions options;
  options.first_plan = &plan;
  planOptions(request, task.scene.hasRobot(), &monitor, options.replan);
  options.replan.verify = false;  // each replan the fastest answer, as closed_loop_demo.py asks
  options.plant.discretization.num_stages = config_.verification_stages;
  options.plant.discretization.num_elements = config_.verification_elements;
  options.plant.homotopy.ipopt.linear_solver = config_.linear_solver;
  options.plant.retry_homotopy.ipopt.linear_solver = config_.linear_solver;
  const fesd::ClosedLoopRun run = fesd::executeWithFeedback(task, config_.limits, options);
  if (run.status != fesd::SolveStatus::kSuccess) {
    ROS_WARN_STREAM("fesd_trajopt: ~targets: execution with feedback failed: " << run.message);
    return;
  }
  // The executed motion in place of the plan's: the answer's paths, markers and playback.
  fesd::SceneOutcome executed = plan;
  executed.trajectory = run.executed;
  executed.verified = false;
  executed.refinements.clear();
  executed.target_yaw_distances.clear();
  executed.target_distances.assign(task.bodies.size(), std::numeric_limits<double>::quiet_NaN());
  std::ostringstream message;
  message << "executed with feedback against the simulated plant: " << run.message;
  bool missed = false;  // judged as a plan's targets: targetTolerance of the length scale
  for (size_t b = 0; b < task.bodies.size(); ++b) {
    if (!task.bodies[b].hasTarget()) continue;
    executed.target_distances[b] =
        (task.scene.position(static_cast<int>(b), run.end) - task.bodies[b].target).norm();
    missed = missed || executed.target_distances[b] >
                           plan.length_scale * fesd::targetTolerance(task.bodies[b].target_weight);
    message << "; '" << task.scene.bodies()[b].name << "' ends " << executed.target_distances[b]
            << " from its target";
  }
  fesd_trajopt::Solution solution = sceneSolution(task, executed, build.planar_joints);
  solution.status =
      statusCode(missed ? fesd::SolveStatus::kTargetNotReached : fesd::SolveStatus::kSuccess);
  solution.message = message.str();
  solution.header.stamp = ros::Time::now();
  solution.header.frame_id = config_.frame_id;
  solution.statistics.wall_time = stopwatch.wallSeconds();
  solution.statistics.cpu_time = stopwatch.cpuSeconds();
  ROS_INFO_STREAM("fesd_trajopt: ~targets: " << solution.message << " in " << run.replan_seconds
                                             << " s of replans");
  publish(task, solution);
}

void TrajoptNode::publish(const fesd::SceneTask& task, const fesd_trajopt::Solution& solution,
                          const std::vector<fesd::PushLeg>& legs,
                          const std::vector<fesd::Transit>& transits) {
  std::lock_guard<std::mutex> lock(publish_mutex_);
  solution_publisher_.publish(solution);
  marker_publisher_.publish(sceneMarkers(task, solution, config_.frame_id, legs, transits));
  // A robot's root is the scene's origin: robot_state_publisher's TF tree hangs from it.
  const std::string root = task.scene.hasRobot() ? task.scene.robot().root_link : "";
  if (!root.empty() && root != config_.frame_id) {
    geometry_msgs::TransformStamped frame;
    frame.header.stamp = ros::Time::now();
    frame.header.frame_id = config_.frame_id;
    frame.child_frame_id = root;
    frame.transform.rotation.w = 1.0;
    frame_broadcaster_.sendTransform(frame);
  }
  publishPaths(solution);
  playback_.play(solution, task.scene.dimension() == 2);
}

void TrajoptNode::publishPaths(const fesd_trajopt::Solution& solution) {
  const std::vector<nav_msgs::Path> paths = bodyPaths(solution);
  for (size_t b = 0; b < paths.size(); ++b) {
    const std::string name = topicName(solution.bodies[b].name);
    auto found = path_publishers_.find(name);
    if (found == path_publishers_.end()) {
      found = path_publishers_
                  .emplace(name, private_node_.advertise<nav_msgs::Path>("paths/" + name, 1, true))
                  .first;
    }
    found->second.publish(paths[b]);
  }
}

void TrajoptNode::handleSimulate(const fesd_trajopt::Simulate::Request& request,
                                 fesd_trajopt::Simulate::Response& response) {
  fesd::Stopwatch stopwatch;
  const Discretization grid = discretization(request, config_);
  if (!grid.error.empty()) return refuse(response, grid.error);
  fesd::SimulationOptions options;
  options.discretization.num_elements = grid.elements;
  options.discretization.num_stages = grid.stages;
  options.wall_time_budget = wallTimeBudget(request, config_);
  options.homotopy.ipopt.linear_solver = config_.linear_solver;
  options.retry_homotopy.ipopt.linear_solver = config_.linear_solver;
  if (!(options.wall_time_budget > 0.0))
    return refuse(response, "the wall-time budget must be > 0");
  const int steps =
      request.has_num_steps ? static_cast<int>(request.num_steps) : config_.num_intervals;
  if (steps < 1 || steps > config_.limits.max_intervals) {
    return refuse(response,
                  "num_steps must be in 1.." + std::to_string(config_.limits.max_intervals));
  }
  options.sensitivities = request.sensitivities;
  if (!request.system.empty()) {
    const std::optional<BuiltinSystem> builtin = builtinSystem(request.system);
    if (!builtin) {
      return refuse(
          response,
          "unknown system '" + request.system +
              "' (\"\" for the scene, or circle_example, two_minus_sign, spiral, sliding)");
    }
    const double horizon = request.has_horizon ? request.horizon : builtin->horizon;
    if (!(horizon > 0.0) || !std::isfinite(horizon) || horizon > config_.limits.max_horizon) {
      return refuse(response, "the horizon must be > 0 and finite");
    }
    Eigen::VectorXd x0 = builtin->initial_state;
    if (!request.initial_state.empty()) {
      if (request.initial_state.size() != static_cast<size_t>(x0.size())) {
        return refuse(response, request.system + " has " + std::to_string(x0.size()) +
                                    " states; initial_state has " +
                                    std::to_string(request.initial_state.size()));
      }
      x0 = Eigen::Map<const Eigen::VectorXd>(request.initial_state.data(), x0.size());
      if (!x0.allFinite()) return refuse(response, "initial_state must be finite");
    }
    const std::string too_many = sensitivitiesTooLarge(request, static_cast<int>(x0.size()), 0,
                                                       steps, config_.max_sensitivity_entries);
    if (!too_many.empty()) return refuse(response, too_many);
    fesd::FesdIntegrator integrator(builtin->model, options);
    const fesd::SimulationResult result = integrator.simulate(x0, horizon, steps);
    fillCommon(result.trajectory, result.totals, response.solution);
    for (const fesd::SwitchEvent& event : result.trajectory.switches) {
      response.solution.switches.push_back(
          switchMessage(event, "x", builtin->constraint_names.at(event.constraint)));
    }
    if (request.sensitivities) {
      response.sensitivities = sensitivityMessage(result.sensitivities, builtin->state_names, {});
    }
    response.solution.message = result.message;
    response.solution.header.stamp = ros::Time::now();
    finish(response, {});
    return;
  }
  TaskBuild build =
      buildTask(config_, sceneFields(request), {request.joints, false, ""}, private_node_);
  if (!build.error.empty()) return refuse(response, build.error);
  fesd::SceneTask& task = build.task;
  if (request.has_horizon) task.horizon = request.horizon;
  task.num_intervals = steps;
  if (!request.initial_state.empty()) {
    return refuse(response,
                  "initial_state is for built-in systems; a scene starts where its "
                  "bodies and joints are");
  }
  const std::string too_many =
      sensitivitiesTooLarge(request, task.scene.stateSize(), task.scene.controlSize(), steps,
                            config_.max_sensitivity_entries);
  if (!too_many.empty()) return refuse(response, too_many);
  std::vector<Eigen::VectorXd> controls(steps, Eigen::VectorXd::Zero(task.scene.controlSize()));
  std::string problem = bodyCommands(request.commands, task.scene, controls);
  if (problem.empty()) problem = jointCommands(request.joint_commands, task.scene, controls);
  if (!problem.empty()) return refuse(response, problem);
  const fesd::SceneOutcome outcome =
      fesd::simulateSceneTask(task, controls, config_.limits, options);
  if (!outcome.invalid.empty()) return refuse(response, outcome.invalid);
  response.solution = sceneSolution(task, outcome, build.planar_joints);
  response.solution.message = outcome.message;
  response.solution.header.stamp = ros::Time::now();
  response.solution.header.frame_id = config_.frame_id;
  if (request.sensitivities) {
    response.sensitivities = sensitivityMessage(outcome.sensitivities, sceneStateNames(task.scene),
                                                sceneControlNames(task.scene));
  }
  response.solution.statistics.wall_time = stopwatch.wallSeconds();
  finish(response, build.notes);
}

}  // namespace fesd_ros
