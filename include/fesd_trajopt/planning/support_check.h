#pragma once

#include <vector>

#include "fesd_trajopt/discretization/trajectory.h"
#include "fesd_trajopt/scene/scene_task.h"

namespace fesd {

/// A support may push its body, never pull it: per free body on a support (Scene::supportOf), how
/// far the plan's contact forces would lift it off: the time integral of the positive part of
/// their component along the support's normal, that is, the height the body would rise by were
/// it not held (scene units; 0 where the support only pushed, and for bodies without one).
/// `plan` is a trajectory of `task` whose multipliers' rows are `modelled`.
std::vector<double> supportLifts(const SceneTask& task, const Trajectory& plan,
                                 const std::vector<ContactPair>& modelled);

}  // namespace fesd
