#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/integrator/fesd_integrator.h"
#include "fesd_trajopt/scene/scene.h"

namespace fesd {

/// Seeded random simulation scenes of the kind users push around: an actuated disc or sphere
/// moving with a constant velocity into 1 to 3 passive ones, sometimes towards a wall, in 2-D or
/// 3-D. The first contact falls at a chosen offset inside a step of a chosen grid, often within
/// 1 % of the step's start or end, where step solves are hardest.
namespace push_scenes {

/// The simulation grids the sweep uses (steps over the horizon).
const std::vector<int>& sweepGrids();

struct PushScene {
  unsigned seed = 0;
  Scene scene{2};            ///< body 0 is the pusher
  Eigen::VectorXd velocity;  ///< the pusher's constant velocity (the only control)
  double horizon = 1.0;
  double contact_time = 0.0;  ///< the pusher touches body 1
  int offset_grid = 0;        ///< the grid (steps) in which that contact has the chosen offset
  double offset = 0.0;        ///< its position inside that grid's step, in (0, 1)

  /// Every pair of the scene (all modelled).
  std::vector<ContactPair> pairs() const { return scene.allPairs(); }
  std::shared_ptr<const DcsModel> model() const { return scene.model(pairs()); }
  Eigen::VectorXd initialState() const { return scene.initialState(); }
  /// The pusher's and the first body's radii summed: the scene's unit of length.
  double contactDistance() const;
  /// A pusher and one passive body, no wall: the exact solution is known (exact()).
  bool hasClosedForm() const;
  /// The exact state at time t (hasClosedForm() only). In contact the projection of (u, 0) onto
  /// the tangent cone moves the passive body with (n . u / 2) n and the pusher with the rest
  /// (a central push halves the speed); the pair's normal n turns away from u, the angle phi
  /// between them growing as tan(phi / 2) = tan(phi0 / 2) exp(|u| (t - t_c) / R), until the
  /// pusher passes and lets go at phi = pi / 2 (lambda = n . u / 4R falls to 0 continuously).
  Eigen::VectorXd exact(double t) const;
  /// When the pusher lets go (hasClosedForm() only; infinite for a central push).
  double releaseTime() const;
  /// One line: seed, dimension, bodies, wall, contact time and offset.
  std::string describe() const;
};

/// The scene simulated on `steps` steps under the pusher's constant velocity.
SimulationResult simulate(const PushScene& scene, int steps, const SimulationOptions& options);

/// The state at the horizon to compare against: the closed form, or else a simulation with 4
/// Radau-IIA stages and 2 elements on `fine_steps` steps (empty if that one fails).
Eigen::VectorXd referenceEnd(const PushScene& scene, int fine_steps);

/// Indices of the errors (of consecutive grids) more than `ratio` times above both neighbours',
/// every error first raised to at least `floor` (round-off is no signal). The coarsest and
/// finest grid have one neighbour and are not judged: at the coarse end FESD's element lengths
/// alone move the error by 2^(2 n_s - 1) (a switch near a step's end leaves the other element
/// nearly 2 h0 long).
std::vector<int> outliers(const std::vector<double>& errors, double ratio = 100.0,
                          double floor = 1e-10);

/// The scene of a seed: deterministic on every machine (its own uniform numbers from the raw
/// output of std::mt19937). Bodies start apart (gaps of at least 0.05) and on the free side of
/// the wall.
PushScene randomPushScene(unsigned seed);

}  // namespace push_scenes
}  // namespace fesd
