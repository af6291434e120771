#include "sensitivity_message.h"

#include <cstdint>

namespace fesd_ros {
namespace {

/// A row-major array with its dims (label, size) and strides (each the product of its own and
/// the later sizes, as std_msgs/MultiArrayLayout defines them).
std_msgs::Float64MultiArray multiArray(const std::vector<std::pair<std::string, int>>& dims) {
  std_msgs::Float64MultiArray array;
  array.layout.dim.resize(dims.size());
  uint32_t stride = 1;
  for (size_t i = dims.size(); i-- > 0;) {
    stride *= static_cast<uint32_t>(dims[i].second);
    array.layout.dim[i].label = dims[i].first;
    array.layout.dim[i].size = static_cast<uint32_t>(dims[i].second);
    array.layout.dim[i].stride = stride;
  }
  return array;
}

/// Appends the columns [first, first + count) of `matrix`, row by row.
void appendRows(const Eigen::MatrixXd& matrix, int first, int count, std::vector<double>& data) {
  for (int i = 0; i < matrix.rows(); ++i) {
    for (int j = first; j < first + count; ++j) data.push_back(matrix(i, j));
  }
}

const char* const kAxes[] = {"x", "y", "z"};

}  // namespace

double sensitivityEntries(int state_size, int control_size, int steps) {
  return static_cast<double>(steps) * state_size * (state_size + double(steps) * control_size);
}

std::vector<std::string> sceneStateNames(const fesd::Scene& scene) {
  std::vector<std::string> names;
  for (int j = 0; j < scene.numJoints(); ++j) names.push_back(scene.robot().joints[j].name);
  for (const fesd::SceneBody& body : scene.bodies()) {
    for (int d = 0; d < scene.dimension(); ++d) names.push_back(body.name + "/" + kAxes[d]);
    if (body.turns) names.push_back(body.name + "/s");  // rho yaw
  }
  return names;
}

std::vector<std::string> sceneControlNames(const fesd::Scene& scene) {
  std::vector<std::string> names;
  for (int j = 0; j < scene.numJoints(); ++j) names.push_back(scene.robot().joints[j].name);
  for (const fesd::SceneBody& body : scene.bodies()) {
    if (!body.actuated) continue;
    for (int d = 0; d < scene.dimension(); ++d) names.push_back(body.name + "/v" + kAxes[d]);
  }
  return names;
}

fesd_trajopt::Sensitivities sensitivityMessage(const fesd::SimulationSensitivities& sensitivities,
                                               std::vector<std::string> state_names,
                                               std::vector<std::string> control_names) {
  fesd_trajopt::Sensitivities message;
  const int nx = static_cast<int>(state_names.size());
  const int steps = static_cast<int>(sensitivities.states.size());
  const int controls = steps == 0 ? 0 : static_cast<int>(sensitivities.states[0].cols()) - nx;
  const int switches = static_cast<int>(sensitivities.switch_times.size());
  message.state_by_initial_state =
      multiArray({{"step", steps}, {"state", nx}, {"initial_state", nx}});
  message.state_by_controls = multiArray({{"step", steps}, {"state", nx}, {"control", controls}});
  message.switch_time_by_initial_state = multiArray({{"switch", switches}, {"initial_state", nx}});
  message.switch_time_by_controls = multiArray({{"switch", switches}, {"control", controls}});
  for (const Eigen::MatrixXd& state : sensitivities.states) {
    appendRows(state, 0, nx, message.state_by_initial_state.data);
    appendRows(state, nx, controls, message.state_by_controls.data);
  }
  bool switches_defined = true;
  for (const Eigen::RowVectorXd& row : sensitivities.switch_times) {
    appendRows(row, 0, nx, message.switch_time_by_initial_state.data);
    appendRows(row, nx, controls, message.switch_time_by_controls.data);
    switches_defined = switches_defined && row.allFinite();
  }
  message.state_names = std::move(state_names);
  message.control_names = std::move(control_names);
  message.defined_steps = static_cast<uint32_t>(sensitivities.defined_steps);
  message.all_defined = sensitivities.defined_steps == steps && switches_defined;
  message.undefined_reason = sensitivities.why_undefined;
  return message;
}

}  // namespace fesd_ros
