#include "fesd_trajopt/discretization/refined_trajectory.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace fesd {
namespace {

/// The polynomial of degree n_s - 1 through the values at `nodes` (columns of `values`), at t.
Eigen::VectorXd stagePolynomial(const Eigen::VectorXd& nodes, const Eigen::MatrixXd& values,
                                double t) {
  Eigen::VectorXd result = Eigen::VectorXd::Zero(values.rows());
  for (int i = 0; i < nodes.size(); ++i) {
    double basis = 1.0;
    for (int j = 0; j < nodes.size(); ++j) {
      if (j != i) basis *= (t - nodes(j)) / (nodes(i) - nodes(j));
    }
    result += basis * values.col(i);
  }
  return result;
}

/// How many parts each of an interval's elements (their lengths) is split into, `count` in all:
/// evenly, the remainder to the longest (the earlier of equal ones).
std::vector<int> splitCounts(const std::vector<double>& lengths, int count) {
  const int elements = static_cast<int>(lengths.size());
  std::vector<int> parts(elements, count / elements);
  std::vector<int> order(elements);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return lengths[a] > lengths[b]; });
  for (int i = 0; i < count % elements; ++i) ++parts[order[i]];
  return parts;
}

}  // namespace

std::vector<int> elementsPerInterval(const Trajectory& trajectory) {
  std::vector<int> counts(trajectory.controls.size(), 0);
  for (const ElementValues& element : trajectory.elements) ++counts.at(element.interval);
  return counts;
}

Trajectory laterPart(const Trajectory& trajectory, int first) {
  const int intervals = static_cast<int>(trajectory.controls.size());
  if (first < 0 || first >= intervals) {
    throw std::invalid_argument("laterPart: no such control interval");
  }
  const double shift = trajectory.interval_times[first];
  Trajectory later;
  later.stage_nodes = trajectory.stage_nodes;
  later.controls.assign(trajectory.controls.begin() + first, trajectory.controls.end());
  for (size_t k = first; k < trajectory.interval_times.size(); ++k) {
    later.interval_times.push_back(trajectory.interval_times[k] - shift);
  }
  for (size_t e = 0; e < trajectory.elements.size(); ++e) {
    if (trajectory.elements[e].interval < first) continue;
    if (later.elements.empty()) {
      later.times.push_back(trajectory.times[e] - shift);
      later.states.push_back(trajectory.states[e]);
    }
    ElementValues element = trajectory.elements[e];
    element.interval -= first;
    element.start_time -= shift;
    later.elements.push_back(std::move(element));
    later.times.push_back(trajectory.times[e + 1] - shift);
    later.states.push_back(trajectory.states[e + 1]);
  }
  return later;
}

Trajectory refinedTrajectory(const Trajectory& solution, const std::vector<int>& interval_elements,
                             const Eigen::VectorXd& stage_nodes) {
  const std::vector<int> counts = elementsPerInterval(solution);
  if (interval_elements.size() != counts.size()) {
    throw std::invalid_argument("refinedTrajectory: one element count per interval");
  }
  Trajectory refined;
  refined.controls = solution.controls;
  refined.interval_times = solution.interval_times;
  refined.stage_nodes = stage_nodes;
  refined.times.push_back(solution.times.front());
  refined.states.push_back(solution.states.front());
  const Eigen::VectorXd& nodes = solution.stage_nodes;
  size_t e = 0;
  for (size_t k = 0; k < counts.size(); ++k) {
    if (interval_elements[k] < counts[k]) {
      throw std::invalid_argument("refinedTrajectory: fewer elements than the solution has");
    }
    std::vector<double> lengths;
    for (int j = 0; j < counts[k]; ++j) lengths.push_back(solution.elements[e + j].step);
    const std::vector<int> parts = splitCounts(lengths, interval_elements[k]);
    for (int j = 0; j < counts[k]; ++j, ++e) {
      const ElementValues& old = solution.elements[e];
      const Eigen::VectorXd& start = solution.states[e];
      for (int p = 0; p < parts[j]; ++p) {
        const double r = parts[j];
        ElementValues element;
        element.interval = old.interval;
        element.start_time = old.start_time + p / r * old.step;
        element.step = old.step / r;
        element.stage_states.resize(old.stage_states.rows(), stage_nodes.size());
        element.stage_multipliers.resize(old.stage_multipliers.rows(), stage_nodes.size());
        for (int i = 0; i < stage_nodes.size(); ++i) {
          const double t = (p + stage_nodes(i)) / r;
          element.stage_states.col(i) = collocationState(nodes, start, old.stage_states, t);
          element.stage_multipliers.col(i) =
              stagePolynomial(nodes, old.stage_multipliers, t).cwiseMax(0.0);
        }
        element.stage_constraints =
            Eigen::MatrixXd::Zero(old.stage_multipliers.rows(), stage_nodes.size());
        refined.elements.push_back(std::move(element));
        const bool last = p + 1 == parts[j];
        refined.times.push_back(last ? solution.times[e + 1]
                                     : old.start_time + (p + 1) / r * old.step);
        refined.states.push_back(
            last ? solution.states[e + 1]
                 : collocationState(nodes, start, old.stage_states, (p + 1) / r));
      }
    }
  }
  return refined;
}

}  // namespace fesd
