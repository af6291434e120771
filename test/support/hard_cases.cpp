#include "support/hard_cases.h"

#include <cmath>
#include <cstdio>

#include "fesd_trajopt/function/affine_function.h"

namespace hard_cases {

fesd::SimulationOptions fesdOptions(int stages, int elements, double step_bound) {
  fesd::SimulationOptions options;
  options.discretization.num_stages = stages;
  options.discretization.num_elements = elements;
  options.discretization.step_bound = step_bound;
  return options;
}

fesd::SimulationOptions fixedElementCountOptions(int stages, int elements) {
  fesd::SimulationOptions options = fesdOptions(stages, elements);
  options.refine_elements = false;
  return options;
}

std::shared_ptr<const fesd::DcsModel> affineModel(const Eigen::MatrixXd& F,
                                                  const Eigen::VectorXd& f0,
                                                  const Eigen::MatrixXd& A,
                                                  const Eigen::VectorXd& b) {
  const int nx = static_cast<int>(F.rows()), nc = static_cast<int>(A.rows());
  Eigen::MatrixXd velocity(nx, nx + nc);  // on z = (x, lambda)
  velocity << F, A.transpose();
  return std::make_shared<fesd::DcsModel>(
      nx, 0, nc, std::make_shared<fesd::AffineFunction>(velocity.sparseView(), f0),
      std::make_shared<fesd::AffineFunction>(A.sparseView(), b), "affine_hard_case");
}

std::shared_ptr<const fesd::DcsModel> PointScene::model() const {
  return scene.model(scene.allPairs());
}

PointScene pointScene(const Eigen::Vector2d& start) {
  PointScene point;
  point.scene.bodies().push_back({"point", 0.0, start, true});
  return point;
}

PointScene cornerScene(const Eigen::Vector2d& start) {
  PointScene point = pointScene(start);
  point.scene.walls().push_back({"floor", Eigen::Vector2d(0.0, 1.0), 0.0});
  point.scene.walls().push_back({"oblique", Eigen::Vector2d(1.0, 1.0) / std::sqrt(2.0), 0.0});
  return point;
}

Eigen::Vector2d DiscRelease::start() const {
  return {-2.0 * radius, radius * std::sin(theta0)};
}
double DiscRelease::contactTime() const {
  return radius * (2.0 + std::cos(theta0)) / speed;
}
double DiscRelease::releaseTime() const {
  return contactTime() + radius / speed * std::log(std::tan(0.5 * theta0));
}
Eigen::VectorXd DiscRelease::exact(double t) const {
  if (t <= contactTime()) return Eigen::Vector2d(start() + t * velocity());
  if (t >= releaseTime()) return Eigen::Vector2d(speed * (t - releaseTime()), radius);
  const double theta =
      2.0 * std::atan(std::tan(0.5 * theta0) * std::exp(-speed * (t - contactTime()) / radius));
  return Eigen::Vector2d(radius * std::cos(theta), radius * std::sin(theta));
}
std::shared_ptr<const fesd::DcsModel> DiscRelease::model() const {
  PointScene point = pointScene(start());
  point.scene.obstacles().push_back({"disc", radius, Eigen::Vector2d::Zero()});
  return point.model();
}

namespace {

bool sameMatrix(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() && (a.array() == b.array()).all();
}

bool sameTrajectory(const fesd::Trajectory& a, const fesd::Trajectory& b) {
  if (a.times != b.times || a.states.size() != b.states.size() ||
      a.elements.size() != b.elements.size()) {
    return false;
  }
  for (size_t n = 0; n < a.states.size(); ++n) {
    if (!sameMatrix(a.states[n], b.states[n])) return false;
  }
  for (size_t n = 0; n < a.elements.size(); ++n) {
    const fesd::ElementValues &p = a.elements[n], &q = b.elements[n];
    if (p.step != q.step || !sameMatrix(p.stage_states, q.stage_states) ||
        !sameMatrix(p.stage_multipliers, q.stage_multipliers) ||
        !sameMatrix(p.stage_constraints, q.stage_constraints)) {
      return false;
    }
  }
  return true;
}

bool allFinite(const fesd::Trajectory& trajectory) {
  for (double t : trajectory.times) {
    if (!std::isfinite(t)) return false;
  }
  for (const Eigen::VectorXd& x : trajectory.states) {
    if (!x.allFinite()) return false;
  }
  for (const fesd::ElementValues& e : trajectory.elements) {
    if (!std::isfinite(e.step) || !e.stage_states.allFinite() || !e.stage_multipliers.allFinite() ||
        !e.stage_constraints.allFinite()) {
      return false;
    }
  }
  return true;
}

}  // namespace

CheckedRun simulateTwice(std::shared_ptr<const fesd::DcsModel> model,
                         const fesd::SimulationOptions& options, const Eigen::VectorXd& x0,
                         double horizon, int steps, const std::vector<Eigen::VectorXd>& controls) {
  CheckedRun run;
  fesd::FesdIntegrator first(model, options), second(model, options);
  run.result = first.simulate(x0, horizon, steps, controls);
  const fesd::SimulationResult again = second.simulate(x0, horizon, steps, controls);
  run.identical =
      again.status == run.result.status && sameTrajectory(again.trajectory, run.result.trajectory);
  return run;
}

::testing::AssertionResult isHealthy(const CheckedRun& run, double residual_bound) {
  const fesd::SimulationResult& r = run.result;
  if (r.status != fesd::SolveStatus::kSuccess) {
    return ::testing::AssertionFailure()
           << "status " << fesd::statusName(r.status) << ": " << r.message;
  }
  if (!(r.totals.complementarity_residual <= residual_bound)) {
    return ::testing::AssertionFailure()
           << "complementarity residual " << r.totals.complementarity_residual << " > "
           << residual_bound;
  }
  if (!allFinite(r.trajectory)) return ::testing::AssertionFailure() << "NaN or Inf in the result";
  if (!r.trajectory.switchesResolved()) {
    return ::testing::AssertionFailure()
           << fesd::describeUnresolvedSwitches(r.trajectory.unresolved_switches);
  }
  if (!run.identical) return ::testing::AssertionFailure() << "two runs differ";
  recordNumber("complementarity_residual", r.totals.complementarity_residual);
  return ::testing::AssertionSuccess();
}

void recordNumber(const std::string& key, double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  ::testing::Test::RecordProperty(key, text);
}

double maxGridError(const fesd::Trajectory& trajectory,
                    const std::function<Eigen::VectorXd(double)>& exact) {
  double error = 0.0;
  for (size_t n = 0; n < trajectory.times.size(); ++n) {
    error = std::max(error, (trajectory.states[n] - exact(trajectory.times[n])).norm());
  }
  return error;
}

double maxMultiplier(const fesd::Trajectory& trajectory, int constraint) {
  double largest = 0.0;
  for (const fesd::ElementValues& e : trajectory.elements) {
    largest = std::max(largest, e.stage_multipliers.row(constraint).maxCoeff());
  }
  return largest;
}

std::vector<fesd::SwitchEvent> switchesOf(const fesd::Trajectory& trajectory, int constraint) {
  std::vector<fesd::SwitchEvent> events;
  for (const fesd::SwitchEvent& event : trajectory.switches) {
    if (event.constraint == constraint) events.push_back(event);
  }
  return events;
}

}  // namespace hard_cases
