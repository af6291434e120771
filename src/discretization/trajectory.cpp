#include "fesd_trajopt/discretization/trajectory.h"

#include <algorithm>
#include <limits>
#include <sstream>

namespace fesd {

void Trajectory::append(const Trajectory& next) {
  if (times.empty()) {
    *this = next;
    return;
  }
  times.insert(times.end(), next.times.begin() + 1, next.times.end());
  states.insert(states.end(), next.states.begin() + 1, next.states.end());
  elements.insert(elements.end(), next.elements.begin(), next.elements.end());
  controls.insert(controls.end(), next.controls.begin(), next.controls.end());
  interval_times.insert(interval_times.end(), next.interval_times.begin() + 1,
                        next.interval_times.end());
  // Classification depends on the whole history: detectSwitches() and findUnresolvedSwitches()
  // again.
  switches.clear();
  unresolved_switches.clear();
}

std::vector<SwitchEvent> detectSwitches(const std::vector<ElementValues>& elements,
                                        const std::vector<bool>& initially_active,
                                        double activity_tolerance) {
  std::vector<SwitchEvent> events;
  std::vector<bool> active = initially_active;
  for (size_t e = 0; e < elements.size(); ++e) {
    const ElementValues& element = elements[e];
    for (int k = 0; k < static_cast<int>(active.size()); ++k) {
      const double multiplier_sum = element.stage_multipliers.row(k).sum();
      const double constraint_sum = element.stage_constraints.row(k).cwiseMax(0.0).sum();
      if (std::max(multiplier_sum, constraint_sum) <= activity_tolerance) continue;
      const bool now_active = multiplier_sum > constraint_sum;
      if (now_active != active[k]) {
        events.push_back({element.start_time, k,
                          now_active ? SwitchEvent::Kind::kContact : SwitchEvent::Kind::kRelease,
                          static_cast<int>(e)});
        active[k] = now_active;
      }
    }
  }
  return events;
}

std::vector<double> collocationWeights(const Eigen::VectorXd& nodes, double t) {
  const int points = static_cast<int>(nodes.size()) + 1;
  auto node = [&](int i) { return i == 0 ? 0.0 : nodes(i - 1); };
  std::vector<double> weights(points, 1.0);
  for (int i = 0; i < points; ++i) {  // Lagrange basis polynomial i at t
    for (int j = 0; j < points; ++j) {
      if (j != i) weights[i] *= (t - node(j)) / (node(i) - node(j));
    }
  }
  return weights;
}

Eigen::VectorXd collocationState(const Eigen::VectorXd& nodes, const Eigen::VectorXd& start_state,
                                 const Eigen::MatrixXd& stage_states, double t) {
  const std::vector<double> weights = collocationWeights(nodes, t);
  Eigen::VectorXd state = weights[0] * start_state;
  for (int i = 1; i < static_cast<int>(weights.size()); ++i) {
    state += weights[i] * stage_states.col(i - 1);
  }
  return state;
}

std::vector<Eigen::VectorXd> densePath(const Trajectory& trajectory, int samples_per_gap) {
  std::vector<Eigen::VectorXd> path;
  const Eigen::VectorXd& nodes = trajectory.stage_nodes;
  for (size_t e = 0; e < trajectory.elements.size(); ++e) {
    const ElementValues& element = trajectory.elements[e];
    const Eigen::VectorXd& start = trajectory.states[e];
    if (e == 0) path.push_back(start);  // later starts are the previous elements' ends
    double previous_node = 0.0;
    for (int i = 0; i < nodes.size(); ++i) {
      for (int sample = 1; sample <= samples_per_gap; ++sample) {
        const double t = previous_node + (nodes(i) - previous_node) * sample /
                                             static_cast<double>(samples_per_gap + 1);
        path.push_back(collocationState(nodes, start, element.stage_states, t));
      }
      path.push_back(element.stage_states.col(i));
      previous_node = nodes(i);
    }
    if (nodes.size() == 0 || nodes(nodes.size() - 1) < 1.0)
      path.push_back(trajectory.states[e + 1]);
  }
  if (trajectory.elements.empty() && !trajectory.states.empty())
    path.push_back(trajectory.states[0]);
  return path;
}

Eigen::VectorXd lowestConstraintBetweenStages(const SmoothFunction& constraints,
                                              const Eigen::VectorXd& nodes,
                                              const Eigen::VectorXd& start_state,
                                              const Eigen::MatrixXd& stage_states,
                                              int samples_per_gap) {
  Eigen::VectorXd tau(nodes.size() + 1);
  tau << 0.0, nodes;
  Eigen::VectorXd lowest =
      Eigen::VectorXd::Constant(constraints.outputSize(), std::numeric_limits<double>::infinity());
  const SparsityPattern& pattern = constraints.jacobianPattern();
  Eigen::VectorXd c(constraints.outputSize()), gradient_norm(constraints.outputSize());
  std::vector<double> jacobian(pattern.nonzeros());
  for (int gap = 0; gap + 1 < tau.size(); ++gap) {
    for (int sample = 1; sample <= samples_per_gap; ++sample) {
      const double t =
          tau(gap) + (tau(gap + 1) - tau(gap)) * sample / static_cast<double>(samples_per_gap + 1);
      const Eigen::VectorXd state = collocationState(nodes, start_state, stage_states, t);
      constraints.evaluate(state.data(), c.data());
      constraints.evaluateJacobian(state.data(), jacobian.data());
      gradient_norm.setZero();
      for (int i = 0; i < pattern.nonzeros(); ++i) {
        gradient_norm(pattern.rows[i]) += jacobian[i] * jacobian[i];
      }
      // c / |grad c|: to first order the signed distance from the constraint's boundary.
      const Eigen::VectorXd distance =
          c.array() / gradient_norm.array().sqrt().max(std::numeric_limits<double>::min());
      lowest = lowest.cwiseMin(distance);
    }
  }
  return lowest;
}

ClosestApproach closestApproach(const SmoothFunction& constraints, int constraint,
                                const Eigen::VectorXd& nodes, const Eigen::VectorXd& start_state,
                                const Eigen::MatrixXd& stage_states, int samples_per_gap) {
  const SparsityPattern& pattern = constraints.jacobianPattern();
  Eigen::VectorXd c(constraints.outputSize());
  std::vector<double> jacobian(pattern.nonzeros());
  const auto distance = [&](double t) {
    const Eigen::VectorXd state = collocationState(nodes, start_state, stage_states, t);
    constraints.evaluate(state.data(), c.data());
    constraints.evaluateJacobian(state.data(), jacobian.data());
    double squared_norm = 0.0;
    for (int i = 0; i < pattern.nonzeros(); ++i) {
      if (pattern.rows[i] == constraint) squared_norm += jacobian[i] * jacobian[i];
    }
    return c(constraint) / std::max(std::sqrt(squared_norm), std::numeric_limits<double>::min());
  };
  const int samples = static_cast<int>(nodes.size()) * (samples_per_gap + 1);
  int lowest = 0;
  double lowest_value = distance(0.0);
  for (int i = 1; i <= samples; ++i) {
    const double value = distance(static_cast<double>(i) / samples);
    if (value < lowest_value) {
      lowest = i;
      lowest_value = value;
    }
  }
  double a = std::max(0.0, (lowest - 1.0) / samples), b = std::min(1.0, (lowest + 1.0) / samples);
  const double ratio = (std::sqrt(5.0) - 1.0) / 2.0;
  double x1 = b - ratio * (b - a), x2 = a + ratio * (b - a);
  double f1 = distance(x1), f2 = distance(x2);
  while (b - a > 1e-9) {
    if (f1 < f2) {
      b = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - ratio * (b - a);
      f1 = distance(x1);
    } else {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + ratio * (b - a);
      f2 = distance(x2);
    }
  }
  if (lowest_value <= std::min(f1, f2)) {
    return {lowest_value, static_cast<double>(lowest) / samples};
  }
  return f1 < f2 ? ClosestApproach{f1, x1} : ClosestApproach{f2, x2};
}

std::vector<UnresolvedSwitch> findUnresolvedSwitches(const std::vector<ElementValues>& elements,
                                                     double activity_tolerance,
                                                     double penetration_tolerance) {
  std::vector<UnresolvedSwitch> unresolved;
  for (size_t e = 0; e < elements.size(); ++e) {
    const ElementValues& element = elements[e];
    for (int k = 0; k < element.stage_multipliers.rows(); ++k) {
      bool apart = false, in_contact = false;
      for (int j = 0; j < element.stage_multipliers.cols(); ++j) {
        const double lambda = element.stage_multipliers(k, j), c = element.stage_constraints(k, j);
        if (std::max(lambda, c) <= activity_tolerance) continue;
        (lambda > c ? in_contact : apart) = true;
      }
      const bool passes_through = element.lowest_constraints.size() > k &&
                                  element.lowest_constraints(k) < -penetration_tolerance;
      if ((apart && in_contact) || passes_through) {
        unresolved.push_back({static_cast<int>(e), element.interval, k, element.start_time,
                              element.start_time + element.step, passes_through});
      }
    }
  }
  return unresolved;
}

void classifySwitches(Trajectory& trajectory, const std::vector<bool>& initially_active,
                      double activity_tolerance, double penetration_tolerance) {
  trajectory.switches = detectSwitches(trajectory.elements, initially_active, activity_tolerance);
  trajectory.unresolved_switches =
      findUnresolvedSwitches(trajectory.elements, activity_tolerance, penetration_tolerance);
}

std::string describeUnresolvedSwitches(const std::vector<UnresolvedSwitch>& unresolved) {
  if (unresolved.empty()) return "";
  const UnresolvedSwitch& first = unresolved.front();
  std::ostringstream text;
  text << unresolved.size() << " unresolved switch(es), more than the element boundaries could "
       << "hold (first: constraint " << first.constraint << " "
       << (first.passes_through ? "passed through" : "switching") << " inside element "
       << first.element << " of interval " << first.interval << ", t in [" << first.start_time
       << ", " << first.end_time
       << "]); the solution is not fully accurate there: use more elements per interval";
  return text.str();
}

}  // namespace fesd
