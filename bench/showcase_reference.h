#pragma once

#include "fesd_trajopt/planning/scene_solver.h"

namespace fesd_bench {

/// The showcase solved as a scene task with `options` (the reference the sweeps' ratios are
/// taken against), its line printed after `prefix`; returns its wall time in seconds.
double timeShowcase(const fesd::SceneSolveOptions& options, const char* prefix);

}  // namespace fesd_bench
