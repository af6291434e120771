#include "fesd_trajopt/scene/robot_from_urdf.h"

#include "fesd_trajopt/kinematics/planarity.h"

namespace fesd {

RobotForScene robotForScene(const std::string& urdf_xml, PlanarChoice choice,
                            const KinematicModelOptions& limits) {
  RobotForScene result;
  KinematicModelOptions options = limits;
  options.planar = false;
  KinematicModelResult spatial = buildKinematicModel(urdf_xml, options);
  if (!spatial.error.empty()) {
    result.error = spatial.error;
    return result;
  }
  const std::string leaving = firstJointLeavingPlane(spatial.model);
  if (choice == PlanarChoice::kPlanar && !leaving.empty()) {
    result.error = "the scene cannot be planar: joint '" + leaving +
                   "' moves the robot out of the (x, y) plane";
    return result;
  }
  const bool planar =
      choice == PlanarChoice::kPlanar || (choice == PlanarChoice::kInferred && leaving.empty());
  result.dimension = planar ? 2 : 3;
  if (!planar) {
    result.robot = std::make_shared<const KinematicModel>(std::move(spatial.model));
    return result;
  }
  options.planar = true;  // read again: cylinders normal to the plane become discs
  KinematicModelResult flat = buildKinematicModel(urdf_xml, options);
  if (!flat.error.empty()) {
    result.error = flat.error;
    return result;
  }
  result.robot = std::make_shared<const KinematicModel>(std::move(flat.model));
  return result;
}

}  // namespace fesd
