#include "fesd_trajopt/kinematics/model_units.h"

#include "fesd_trajopt/kinematics/reach.h"

namespace fesd {
namespace {

void scaleTranslation(Eigen::Isometry3d& frame, double factor) {
  frame.translation() *= factor;
}

void scaleSphere(KinematicSphere& sphere, double factor) {
  sphere.local_centre *= factor;
  sphere.joint_centre *= factor;
  sphere.radius *= factor;
}

}  // namespace

KinematicModel withLengthsScaled(const KinematicModel& model, double factor) {
  KinematicModel scaled = model;
  for (KinematicJoint& joint : scaled.joints) {
    scaleTranslation(joint.origin, factor);
    if (joint.type != JointType::kPrismatic) continue;
    joint.lower *= factor;
    joint.upper *= factor;
    joint.max_velocity *= factor;
  }
  for (KinematicLink& link : scaled.links) scaleTranslation(link.offset, factor);
  for (KinematicSphere& sphere : scaled.spheres) scaleSphere(sphere, factor);
  for (FreeLink& free : scaled.free_links) {
    scaleTranslation(free.pose, factor);
    for (KinematicSphere& sphere : free.spheres) scaleSphere(sphere, factor);
  }
  return scaled;
}

KinematicModel inLengthUnits(const KinematicModel& model, double length_scale) {
  const double radians_per_unit = length_scale / robotReach(model);
  KinematicModel scaled = withLengthsScaled(model, 1.0 / length_scale);
  for (KinematicJoint& joint : scaled.joints) {
    if (joint.type == JointType::kPrismatic) continue;
    joint.lower /= radians_per_unit;
    joint.upper /= radians_per_unit;
    joint.max_velocity /= radians_per_unit;
    joint.coordinate_scale *= radians_per_unit;
  }
  return scaled;
}

}  // namespace fesd
