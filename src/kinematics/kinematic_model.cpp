#include "fesd_trajopt/kinematics/kinematic_model.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <utility>

#include <urdf_parser/urdf_parser.h>

#include "fesd_trajopt/kinematics/urdf_pose.h"

namespace fesd {
namespace {

const char* shapeName(int type) {
  switch (type) {
    case urdf::Geometry::SPHERE:
      return "sphere";
    case urdf::Geometry::BOX:
      return "box";
    case urdf::Geometry::CYLINDER:
      return "cylinder";
    case urdf::Geometry::MESH:
      return "mesh";
    default:
      return "unknown shape";
  }
}

/// urdfdom's links own their children, so dropping a long chain would destroy it recursively
/// (one nested destructor per link); unlinking them first keeps the teardown flat.
struct FlatTeardown {
  urdf::ModelInterfaceSharedPtr model;
  ~FlatTeardown() {
    if (!model) return;
    for (auto& entry : model->links_) entry.second->child_links.clear();
  }
};

/// A link still to visit: its nearest moving joint above, its frame in that joint's moved frame
/// and its frame in the world at q = 0.
struct PendingLink {
  urdf::LinkConstSharedPtr link;
  int joint;
  Eigen::Isometry3d offset, zero_pose;
};

class ModelBuilder {
 public:
  ModelBuilder(const urdf::ModelInterface& urdf, const KinematicModelOptions& options)
      : urdf_(urdf), options_(options) {}

  /// Walks the tree depth first with an explicit stack, so parents precede children.
  KinematicModelResult build() {
    KinematicModelResult result;
    model_.root_link = urdf_.getRoot()->name;
    std::vector<PendingLink> stack{
        {urdf_.getRoot(), -1, Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity()}};
    while (!stack.empty()) {
      const PendingLink pending = std::move(stack.back());
      stack.pop_back();
      addLink(pending);
      if (!error_.empty()) break;
      std::vector<PendingLink> children;
      for (const urdf::JointSharedPtr& joint : pending.link->child_joints) {
        followJoint(*joint, pending, children);
        if (!error_.empty()) break;
      }
      if (!error_.empty()) break;
      stack.insert(stack.end(), children.rbegin(), children.rend());  // the first on top
    }
    result.error = error_;
    if (error_.empty()) result.model = std::move(model_);
    return result;
  }

 private:
  void addLink(const PendingLink& pending) {
    const int index = static_cast<int>(model_.links.size());
    model_.links.push_back({pending.link->name, pending.joint, pending.offset});
    addSpheres(*pending.link, index, pending.offset, pending.zero_pose, model_.spheres);
  }

  /// Every `<collision>` sphere of a link (in planar models also every cylinder normal to the
  /// plane at q = 0) into `spheres`, tagged with `link`; other shapes go to ignored_shapes.
  void addSpheres(const urdf::Link& link, int index, const Eigen::Isometry3d& offset,
                  const Eigen::Isometry3d& zero_pose, std::vector<KinematicSphere>& spheres) {
    const auto& collisions = link.collision_array;
    const std::string prefix = link.name + "/";
    for (std::size_t k = 0; k < collisions.size(); ++k) {
      const urdf::Collision& collision = *collisions[k];
      if (!collision.geometry) continue;
      const Eigen::Isometry3d local = isometryFromUrdf(collision.origin);
      double radius = 0.0;
      if (collision.geometry->type == urdf::Geometry::SPHERE) {
        radius = static_cast<const urdf::Sphere&>(*collision.geometry).radius;
      } else if (options_.planar && collision.geometry->type == urdf::Geometry::CYLINDER &&
                 std::abs((zero_pose * local).linear()(2, 2)) > 1.0 - 1e-9) {
        radius = static_cast<const urdf::Cylinder&>(*collision.geometry).radius;
      }
      if (!(radius > 0.0)) {
        model_.ignored_shapes.push_back(prefix + "collision_" + std::to_string(k) + " (" +
                                        shapeName(collision.geometry->type) + ")");
        continue;
      }
      if (++sphere_count_ > options_.max_spheres) {
        error_ = "the URDF has more than " + std::to_string(options_.max_spheres) +
                 " collision spheres (limits/max_spheres)";
        return;
      }
      const Eigen::Vector3d centre = local.translation();
      spheres.push_back(
          {prefix + "sphere_" + std::to_string(k), index, centre, offset * centre, radius});
    }
  }

  /// Adds a moving joint's coordinate or a free link; the child links to visit go to children.
  void followJoint(const urdf::Joint& joint, const PendingLink& parent,
                   std::vector<PendingLink>& children) {
    const urdf::LinkConstSharedPtr child = urdf_.getLink(joint.child_link_name);
    if (!child) return;
    const Eigen::Isometry3d origin = isometryFromUrdf(joint.parent_to_joint_origin_transform);
    switch (joint.type) {
      case urdf::Joint::FIXED:
        children.push_back(
            {child, parent.joint, parent.offset * origin, parent.zero_pose * origin});
        return;
      case urdf::Joint::PLANAR:
      case urdf::Joint::FLOATING:
        model_.free_links.push_back({child->name,
                                     joint.name,
                                     parent.link->name,
                                     joint.type == urdf::Joint::PLANAR,
                                     parent.offset * origin,
                                     Eigen::Vector3d(joint.axis.x, joint.axis.y, joint.axis.z),
                                     !child->child_joints.empty(),
                                     {}});
        addSpheres(*child, -1, parent.offset * origin, parent.zero_pose * origin,
                   model_.free_links.back().spheres);
        return;
      case urdf::Joint::REVOLUTE:
      case urdf::Joint::CONTINUOUS:
      case urdf::Joint::PRISMATIC:
        break;
      default:
        error_ = "joint " + joint.name + " has an unknown type";
        return;
    }
    if (model_.numCoordinates() >= options_.max_coordinates) {
      error_ =
          "the URDF has more than " + std::to_string(options_.max_coordinates) + " moving joints";
      return;
    }
    const Eigen::Vector3d axis(joint.axis.x, joint.axis.y, joint.axis.z);
    if (!(axis.norm() > 1e-12)) {
      error_ = "joint " + joint.name + " has a zero axis";
      return;
    }
    KinematicJoint coordinate;
    coordinate.name = joint.name;
    coordinate.type = joint.type == urdf::Joint::REVOLUTE     ? JointType::kRevolute
                      : joint.type == urdf::Joint::CONTINUOUS ? JointType::kContinuous
                                                              : JointType::kPrismatic;
    coordinate.axis = axis.normalized();
    coordinate.origin = parent.offset * origin;
    coordinate.parent = parent.joint;
    if (parent.joint >= 0) coordinate.chain = model_.joints[parent.joint].chain;
    const int index = model_.numCoordinates();
    coordinate.chain.push_back(index);
    const double infinity = std::numeric_limits<double>::infinity();
    const bool bounded = coordinate.type != JointType::kContinuous && joint.limits;
    coordinate.lower = bounded ? joint.limits->lower : -infinity;
    coordinate.upper = bounded ? joint.limits->upper : infinity;
    coordinate.max_velocity = joint.limits ? joint.limits->velocity : 0.0;
    if (!(coordinate.lower <= coordinate.upper) || !(coordinate.max_velocity >= 0.0)) {
      error_ = "joint " + joint.name + " has limits out of order or a negative velocity limit";
      return;
    }
    model_.joints.push_back(std::move(coordinate));
    children.push_back({child, index, Eigen::Isometry3d::Identity(), parent.zero_pose * origin});
  }

  const urdf::ModelInterface& urdf_;
  const KinematicModelOptions& options_;
  KinematicModel model_;
  int sphere_count_ = 0;  ///< the robot's and its free links'
  std::string error_;
};

template <typename Items>
int indexByName(const Items& items, const std::string& name) {
  const auto found =
      std::find_if(items.begin(), items.end(), [&](const auto& item) { return item.name == name; });
  return found == items.end() ? -1 : static_cast<int>(found - items.begin());
}

}  // namespace

const std::vector<int>& KinematicModel::chainOf(int sphere) const {
  static const std::vector<int> kNoJoints;
  const int joint = links[spheres[sphere].link].joint;
  return joint < 0 ? kNoJoints : joints[joint].chain;
}

int KinematicModel::jointIndex(const std::string& name) const {
  return indexByName(joints, name);
}
int KinematicModel::linkIndex(const std::string& name) const {
  return indexByName(links, name);
}
int KinematicModel::sphereIndex(const std::string& name) const {
  return indexByName(spheres, name);
}

KinematicModelResult buildKinematicModel(const std::string& urdf_xml,
                                         const KinematicModelOptions& options) {
  KinematicModelResult result;
  FlatTeardown parsed;
  try {
    parsed.model = urdf::parseURDF(urdf_xml);
  } catch (const std::exception& error) {
    result.error = std::string("malformed URDF: ") + error.what();
    return result;
  }
  if (!parsed.model || !parsed.model->getRoot()) {
    result.error = "malformed URDF: it could not be parsed";
    return result;
  }
  if (static_cast<int>(parsed.model->links_.size()) > options.max_links) {
    result.error = "the URDF has " + std::to_string(parsed.model->links_.size()) +
                   " links, more than " + std::to_string(options.max_links);
    return result;
  }
  return ModelBuilder(*parsed.model, options).build();
}

}  // namespace fesd
