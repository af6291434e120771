#pragma once

#include <memory>
#include <string>

#include "fesd_trajopt/kinematics/kinematic_model.h"
#include "fesd_trajopt/scene/scene_task.h"

namespace fesd_bench {

/// The showcase plus `rocks` passive discs (R = 1, no target) at (-12 + 4 i, -12): with all seven
/// it is node_roundtrip's ten_discs_in_reach.
fesd::SceneTask showcaseWithRocks(int intervals, int rocks);

/// A robot of config/robots, built from its URDF; throws naming the file if that fails.
std::shared_ptr<const fesd::KinematicModel> shippedRobot(const std::string& file);

}  // namespace fesd_bench
