// The limit surface's turning radius (limit_surface.cpp): the footprint's centre of pressure and
// its mean distance from it, against the closed form of a lone disc (to 2e-5) and a fine
// Cartesian grid (to the grid's own accuracy, 3e-4).
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Geometry>

#include "fesd_trajopt/scene/limit_surface.h"

namespace {

/// The mean distance from `centre` over the union-with-multiplicity of the discs, by midpoints of
/// a fine square grid: an independent reference.
double gridMeanDistance(const fesd::Footprint& footprint, const Eigen::Vector2d& centre) {
  double sum = 0.0, count = 0.0;
  for (size_t k = 0; k < footprint.centres.size(); ++k) {
    const double r = footprint.radii[k];
    const int n = 1200;
    const double h = 2.0 * r / n;
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        const Eigen::Vector2d local(-r + (i + 0.5) * h, -r + (j + 0.5) * h);
        if (local.norm() > r) continue;
        sum += h * h * (footprint.centres[k] + local - centre).norm();
        count += h * h;  // each cell by its area
      }
    }
  }
  return sum / count;
}

TEST(LimitSurface, ALoneDiscTurnsAboutItsCentreWithTwoThirdsOfItsRadius) {
  const fesd::Footprint disc{{Eigen::Vector2d(0.3, -0.2)}, {0.6}};
  const Eigen::Vector2d centre = fesd::pressureCentre(disc);
  EXPECT_LT((centre - Eigen::Vector2d(0.3, -0.2)).norm(), 1e-15);
  EXPECT_NEAR(fesd::limitSurfaceRadius(disc, centre), 2.0 * 0.6 / 3.0, 2e-5 * 0.4);
}

TEST(LimitSurface, AreasWeighTheCentreAndTheMeanDistance) {
  // Radii 1 and 2 (areas 1 : 4) at x = 0 and 3: the centre of pressure at x = 2.4.
  const fesd::Footprint pair{{Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(3.0, 0.0)}, {1.0, 2.0}};
  const Eigen::Vector2d centre = fesd::pressureCentre(pair);
  EXPECT_LT((centre - Eigen::Vector2d(2.4, 0.0)).norm(), 1e-14);
  const double rho = fesd::limitSurfaceRadius(pair, centre);
  const double reference = gridMeanDistance(pair, centre);
  EXPECT_NEAR(rho, reference, 3e-4 * reference);
  // A bar of three discs in a row (overlapping: the overlaps count twice) turned by 30 degrees
  // keeps its radius.
  fesd::Footprint bar{
      {Eigen::Vector2d(-1.0, 0.0), Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(1.0, 0.0)},
      {0.6, 0.6, 0.6}};
  const double straight = fesd::limitSurfaceRadius(bar, Eigen::Vector2d::Zero());
  EXPECT_NEAR(straight, gridMeanDistance(bar, Eigen::Vector2d::Zero()), 3e-4 * straight);
  for (Eigen::Vector2d& c : bar.centres) c = Eigen::Rotation2Dd(M_PI / 6.0) * c;
  EXPECT_NEAR(fesd::limitSurfaceRadius(bar, Eigen::Vector2d::Zero()), straight, 1e-12);
}

}  // namespace
