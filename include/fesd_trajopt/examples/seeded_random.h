#pragma once

#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/Dense>

namespace fesd {

/// Uniform numbers from std::mt19937's raw output: the standard fixes the engine's sequence,
/// not the distributions', so seeded scenes are the same with every standard library.
class SeededUniform {
 public:
  explicit SeededUniform(unsigned seed) : engine_(seed) {}
  double operator()(double low = 0.0, double high = 1.0) {
    return low + (high - low) * (engine_() / 4294967296.0);
  }
  int integer(int low, int high) {  ///< in [low, high]
    return std::min(high, low + static_cast<int>((*this)() * (high - low + 1)));
  }
  /// A unit vector in 2-D or 3-D, uniformly distributed.
  Eigen::VectorXd unitVector(int dim) {
    if (dim == 2) {
      const double angle = (*this)(0.0, 2.0 * M_PI);
      return Eigen::Vector2d(std::cos(angle), std::sin(angle));
    }
    const double z = (*this)(-1.0, 1.0), angle = (*this)(0.0, 2.0 * M_PI);
    const double r = std::sqrt(1.0 - z * z);
    return Eigen::Vector3d(r * std::cos(angle), r * std::sin(angle), z);
  }

 private:
  std::mt19937 engine_;
};

}  // namespace fesd
