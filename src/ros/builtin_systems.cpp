#include "builtin_systems.h"

#include "fesd_trajopt/examples/circle_example.h"
#include "fesd_trajopt/examples/filippov_examples.h"

namespace fesd_ros {

std::optional<BuiltinSystem> builtinSystem(const std::string& name) {
  if (name == "circle_example") {
    return BuiltinSystem{fesd::circle_example::model(),
                         fesd::circle_example::initialState(),
                         fesd::circle_example::horizon(),
                         {"x1", "x2"},
                         {"x2 >= -1"}};
  }
  if (name == "two_minus_sign") {
    return BuiltinSystem{fesd::sign_example::model(),
                         Eigen::VectorXd::Constant(1, -1.0),
                         2.0,
                         {"x"},
                         {"x > 0", "x < 0"}};
  }
  if (name == "spiral") {
    return BuiltinSystem{fesd::spiral_example::model(),
                         fesd::spiral_example::initialState(),
                         fesd::spiral_example::horizon(),
                         {"x1", "x2"},
                         {"|x| > 1", "|x| < 1"}};
  }
  if (name == "sliding") {
    return BuiltinSystem{fesd::sliding_example::model(),
                         fesd::sliding_example::initialState(),
                         fesd::sliding_example::horizon(),
                         {"x1", "x2"},
                         {"x1 > 0", "x1 < 0"}};
  }
  return std::nullopt;
}

}  // namespace fesd_ros
