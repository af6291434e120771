#include "fesd_trajopt/scene/limit_surface.h"

#include <cmath>

namespace fesd {
namespace {

constexpr int kRadialNodes = 128;
constexpr int kAngularNodes = 128;

/// The mean of |p| over a disc of radius r centred at c: midpoints in the radius, the periodic
/// trapezoidal rule in the angle.
double meanDistance(const Eigen::Vector2d& c, double r) {
  double sum = 0.0, weight = 0.0;
  for (int i = 0; i < kRadialNodes; ++i) {
    const double rho = r * (i + 0.5) / kRadialNodes;
    for (int j = 0; j < kAngularNodes; ++j) {
      const double angle = 2.0 * M_PI * j / kAngularNodes;
      sum += rho * (c + rho * Eigen::Vector2d(std::cos(angle), std::sin(angle))).norm();
      weight += rho;
    }
  }
  return sum / weight;
}

}  // namespace

Eigen::Vector2d pressureCentre(const Footprint& footprint) {
  Eigen::Vector2d moment = Eigen::Vector2d::Zero();
  double area = 0.0;
  for (size_t k = 0; k < footprint.centres.size(); ++k) {
    const double a = footprint.radii[k] * footprint.radii[k];
    moment += a * footprint.centres[k];
    area += a;
  }
  return moment / area;
}

double limitSurfaceRadius(const Footprint& footprint, const Eigen::Vector2d& centre) {
  double sum = 0.0, area = 0.0;
  for (size_t k = 0; k < footprint.centres.size(); ++k) {
    const double a = footprint.radii[k] * footprint.radii[k];
    sum += a * meanDistance(footprint.centres[k] - centre, footprint.radii[k]);
    area += a;
  }
  return sum / area;
}

}  // namespace fesd
