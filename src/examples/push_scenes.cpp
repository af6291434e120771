#include "fesd_trajopt/examples/push_scenes.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "fesd_trajopt/examples/seeded_random.h"

namespace fesd {
namespace push_scenes {
namespace {

/// A random unit vector perpendicular to the unit vector d.
Eigen::VectorXd randomPerpendicular(SeededUniform& random, const Eigen::VectorXd& d) {
  if (d.size() == 2) {
    const Eigen::Vector2d normal(-d(1), d(0));
    return random() < 0.5 ? normal : Eigen::Vector2d(-normal);
  }
  for (;;) {
    const Eigen::VectorXd v = random.unitVector(3);
    const Eigen::VectorXd perpendicular = v - v.dot(d) * d;
    if (perpendicular.norm() > 0.1) return perpendicular.normalized();
  }
}

constexpr double kStartGap = 0.05;

bool apart(const Scene& scene, const Eigen::VectorXd& position, double radius) {
  for (const SceneBody& body : scene.bodies()) {
    if ((body.position - position).norm() < body.radius + radius + kStartGap) return false;
  }
  return true;
}

/// The pair's unit normal (pusher to body) at the first contact and its angle to the push.
struct FirstContact {
  Eigen::VectorXd normal;
  double cos_angle, angle;
};

FirstContact firstContact(const PushScene& s) {
  const Eigen::VectorXd normal =
      (s.scene.bodies()[1].position - s.scene.bodies()[0].position - s.contact_time * s.velocity) /
      s.contactDistance();
  const double cos_angle =
      std::max(-1.0, std::min(1.0, normal.dot(s.velocity / s.velocity.norm())));
  return {normal, cos_angle, std::acos(cos_angle)};
}

}  // namespace

const std::vector<int>& sweepGrids() {
  static const std::vector<int> grids{4, 5, 6, 8, 10, 12, 16, 20, 24, 32, 40};
  return grids;
}

double PushScene::contactDistance() const {
  return scene.bodies()[0].radius + scene.bodies()[1].radius;
}

bool PushScene::hasClosedForm() const {
  return scene.bodies().size() == 2 && scene.walls().empty();
}

Eigen::VectorXd PushScene::exact(double t) const {
  const Eigen::VectorXd p0 = scene.bodies()[0].position, q0 = scene.bodies()[1].position;
  const double distance = contactDistance();
  const int dim = scene.dimension();
  Eigen::VectorXd x(2 * dim);
  if (t <= contact_time) {
    x << p0 + t * velocity, q0;
    return x;
  }
  const double speed = velocity.norm();
  const Eigen::VectorXd u_hat = velocity / speed;
  const FirstContact first = firstContact(*this);
  const double cos0 = first.cos_angle, phi0 = first.angle;
  const Eigen::VectorXd across = first.normal - cos0 * u_hat;
  const Eigen::VectorXd e =
      across.norm() > 1e-14 ? Eigen::VectorXd(across.normalized()) : Eigen::VectorXd::Zero(dim);
  const double release = releaseTime();
  const double elapsed = std::min(t, release) - contact_time;
  const double phi = 2.0 * std::atan(std::tan(0.5 * phi0) * std::exp(speed * elapsed / distance));
  // q - q0 = (R / 2) [(ln tan(phi / 2) + cos phi)|_phi0^phi u_hat + (sin phi)|_phi0^phi e], and
  // ln tan(phi / 2) - ln tan(phi0 / 2) = |u| (t - t_c) / R.
  const Eigen::VectorXd q = q0 + 0.5 * distance *
                                     ((speed * elapsed / distance + std::cos(phi) - cos0) * u_hat +
                                      (std::sin(phi) - std::sin(phi0)) * e);
  const Eigen::VectorXd n = std::cos(phi) * u_hat + std::sin(phi) * e;
  x << q - distance * n + std::max(0.0, t - release) * velocity, q;
  return x;
}

double PushScene::releaseTime() const {
  // tan(phi / 2) reaches tan(pi / 4) = 1; a central push (phi0 = 0) never lets go.
  return contact_time +
         contactDistance() / velocity.norm() * -std::log(std::tan(0.5 * firstContact(*this).angle));
}

std::string PushScene::describe() const {
  std::ostringstream text;
  text << "seed " << seed << ": " << scene.dimension() << "-D, " << scene.bodies().size()
       << " bodies" << (scene.walls().empty() ? "" : ", a wall")
       << ", first contact at t = " << contact_time << " of " << horizon << " (offset " << offset
       << " in a step of the " << offset_grid << "-step grid)";
  return text.str();
}

SimulationResult simulate(const PushScene& scene, int steps, const SimulationOptions& options) {
  FesdIntegrator integrator(scene.model(), options);
  return integrator.simulate(scene.initialState(), scene.horizon, steps, {scene.velocity});
}

Eigen::VectorXd referenceEnd(const PushScene& scene, int fine_steps) {
  if (scene.hasClosedForm()) return scene.exact(scene.horizon);
  SimulationOptions fine;
  fine.discretization.num_stages = 4;
  fine.discretization.num_elements = 2;
  const SimulationResult result = simulate(scene, fine_steps, fine);
  return result.status == SolveStatus::kSuccess ? result.trajectory.finalState()
                                                : Eigen::VectorXd();
}

std::vector<int> outliers(const std::vector<double>& errors, double ratio, double floor) {
  std::vector<int> found;
  for (size_t i = 1; i + 1 < errors.size(); ++i) {
    const double error = std::max(errors[i], floor);
    if (error > ratio * std::max(errors[i - 1], floor) &&
        error > ratio * std::max(errors[i + 1], floor)) {
      found.push_back(static_cast<int>(i));
    }
  }
  return found;
}

PushScene randomPushScene(unsigned seed) {
  SeededUniform random(seed);
  PushScene s;
  s.seed = seed;
  const int dim = random() < 0.5 ? 2 : 3;
  s.scene = Scene(dim);
  const double pusher_radius = random(0.5, 1.5), object_radius = random(0.5, 1.5);
  const double distance = pusher_radius + object_radius;
  const double speed = random(0.5, 2.0);
  const Eigen::VectorXd d = random.unitVector(dim), e = randomPerpendicular(random, d);
  s.velocity = speed * d;
  s.horizon = random(2.0, 5.0);
  // The first contact at an offset inside a step of one grid: near the step's start, near its
  // end, or anywhere, in turn.
  const std::vector<int>& grids = sweepGrids();
  s.offset_grid = grids[random.integer(0, static_cast<int>(grids.size()) - 1)];
  switch (seed % 3) {
    case 0:
      s.offset = random(1e-4, 1e-2);
      break;
    case 1:
      s.offset = random(0.99, 1.0 - 1e-4);
      break;
    default:
      s.offset = random(0.01, 0.99);
  }
  const double step = s.horizon / s.offset_grid;
  int k = random.integer(0, std::max(0, s.offset_grid / 2 - 1));
  while ((k + s.offset) * step * speed < 2.0 * kStartGap) ++k;  // start apart
  s.contact_time = (k + s.offset) * step;
  const double impact = random(-0.9, 0.9) * distance;
  const Eigen::VectorXd pusher = Eigen::VectorXd::Zero(dim);
  const Eigen::VectorXd object =
      (s.contact_time * speed + std::sqrt(distance * distance - impact * impact)) * d + impact * e;
  s.scene.bodies().push_back({"pusher", pusher_radius, pusher, true});
  s.scene.bodies().push_back({"object_1", object_radius, object, false});

  // Further passive bodies: ahead of the first (a chain it may push) or beside its path.
  const int extra = random.integer(0, 2);
  for (int i = 0; i < extra; ++i) {
    const double radius = random(0.5, 1.5);
    for (int attempt = 0; attempt < 20; ++attempt) {
      const Eigen::VectorXd side = randomPerpendicular(random, d);
      const double gap = random(0.1, 1.5);
      Eigen::VectorXd position;
      if (random() < 0.5) {
        const double angle = random(-40.0, 40.0) * M_PI / 180.0;
        position = object +
                   (object_radius + radius + gap) * (std::cos(angle) * d + std::sin(angle) * side);
      } else {
        position = object + (object_radius + radius + 2.0 * gap) * side + random(-2.0, 2.0) * d;
      }
      if (apart(s.scene, position, radius)) {
        s.scene.bodies().push_back(
            {"object_" + std::to_string(s.scene.bodies().size()), radius, position, false});
        break;
      }
    }
  }
  // A wall ahead, facing the push, tilted by up to about 40 degrees.
  if (random() < 0.4) {
    const Eigen::VectorXd normal =
        (-d + random(-0.8, 0.8) * randomPerpendicular(random, d)).normalized();
    double offset = std::numeric_limits<double>::infinity();
    for (const SceneBody& body : s.scene.bodies()) {
      offset = std::min(offset, normal.dot(body.position) - body.radius);
    }
    s.scene.walls().push_back({"wall", normal, offset - random(0.3, 2.5)});
  }
  return s;
}

}  // namespace push_scenes
}  // namespace fesd
