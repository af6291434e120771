#pragma once

#include <string>
#include <vector>

#include <fesd_trajopt/Sensitivities.h>

#include "fesd_trajopt/integrator/fesd_integrator.h"
#include "fesd_trajopt/scene/scene.h"

namespace fesd_ros {

/// How many numbers the sensitivities of `steps` steps of a system with n_x states and n_u
/// controls take (states by x0 and by the controls, per step end).
double sensitivityEntries(int state_size, int control_size, int steps);

/// The names of a scene's state components (joints, then each body's <name>/x, /y, /z) and of
/// its control components (joints, then each actuated body's <name>/vx, ...).
std::vector<std::string> sceneStateNames(const fesd::Scene& scene);
std::vector<std::string> sceneControlNames(const fesd::Scene& scene);

/// The Sensitivities message of a simulation's sensitivities (row-major arrays with named dims).
fesd_trajopt::Sensitivities sensitivityMessage(const fesd::SimulationSensitivities& sensitivities,
                                               std::vector<std::string> state_names,
                                               std::vector<std::string> control_names);

}  // namespace fesd_ros
