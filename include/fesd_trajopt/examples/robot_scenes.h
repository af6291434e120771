#pragma once

#include <memory>

#include "fesd_trajopt/scene/scene_task.h"

namespace fesd {

/// The shipped planar-arm push (config/robots/planar_arm.urdf: shoulder, elbow, wrist about z):
/// the arm starts at q0 = (-0.6, 0, 0), pointing below the x axis, and pushes a disc of radius
/// 0.05 at (0.6, 0) to (0.6, 0.2) (weight 100) within 2 s on 10 control intervals, the joints
/// at their URDF speed limits; no joint targets.
SceneTask planarArmPushTask(std::shared_ptr<const KinematicModel> arm);

/// The shipped Panda push (config/robots/panda_spherized.urdf, VAMP's 59 spheres): from the
/// ready pose q0 = (0, -0.785, 0, -2.356, 0, 1.571, 0.785) the arm pushes a puck (a sphere of
/// radius 0.05 resting on the table z >= 0) from (0.45, 0, 0.05) to (0.65, 0, 0.05) (weight 100)
/// within 2 s on 5 control intervals, the joints at their URDF speed limits; no joint targets.
SceneTask pandaPushTask(std::shared_ptr<const KinematicModel> panda);

/// pandaPushTask with a 4 cm puck (radius 0.02, resting on the table), the tabletop issue's.
SceneTask pandaSmallPuckTask(std::shared_ptr<const KinematicModel> panda);

/// A UR3e on a table (config/robots/ur3e_spherized.urdf, its base on the table z >= 0): from
/// q0 = (-0.91, -0.98, 1.52, -1.95, -1.92, 0), its tool sphere above the table, it pushes a puck
/// of radius 0.03 resting on the table from (-0.3, 0.1, 0.03) 0.2 m along -y (weight 100) within
/// 2 s on 8 control intervals.
SceneTask ur3ePushTask(std::shared_ptr<const KinematicModel> ur3e);

/// A planar iiwa (config/robots/planar_iiwa.urdf: joints about z, links 0.42, 0.40, 0.126 m),
/// no table: from q0 = (-0.6, 0, 0) it pushes a disc of radius 0.04 from (0.75, 0) to (0.75, 0.2)
/// (weight 100) within 2 s on 10 control intervals.
SceneTask planarIiwaPushTask(std::shared_ptr<const KinematicModel> iiwa);

/// The Panda brings a bar to a pose on the table: from the ready pose, a bar of three spheres
/// (radius 0.03, 0.05 apart along x) resting on the table z >= 0 at (0.45, 0, 0.03), yaw 0,
/// turning as it slides (its limit surface), to (0.55, 0.07, 0.03) and yaw 0.5 rad (weights 100)
/// within 3 s on 12 control intervals.
SceneTask pandaBarTask(std::shared_ptr<const KinematicModel> panda);

}  // namespace fesd
