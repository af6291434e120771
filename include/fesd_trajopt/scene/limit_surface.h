#pragma once

#include <vector>

#include <Eigen/Dense>

namespace fesd {

/// A body that slides on a table under uniform pressure over the footprints of its spheres
/// (discs of their radii), with the ellipsoidal approximation of its limit surface: its twist is
/// proportional to (F, tau / rho^2) for the wrench (F, tau) about its centre of pressure, rho the
/// ratio of the largest moment to the largest force friction can resist, the footprint's mean
/// distance from that centre (Goyal et al. 1991; Lynch et al. 1992).
struct Footprint {
  std::vector<Eigen::Vector2d> centres;
  std::vector<double> radii;
};

/// The footprint's centre of pressure: its discs' area-weighted centroid.
Eigen::Vector2d pressureCentre(const Footprint& footprint);

/// rho: the footprint's area-weighted mean distance from `centre` (each disc by a fixed polar
/// quadrature, relative error below 2e-5; a lone disc about its centre: 2 r / 3).
double limitSurfaceRadius(const Footprint& footprint, const Eigen::Vector2d& centre);

}  // namespace fesd
