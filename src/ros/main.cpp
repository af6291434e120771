// fesd_trajopt_node: trajectory optimisation with FESD as a ROS service.
#include <ros/ros.h>

#include "fesd_trajopt/solver/heap_policy.h"
#include "trajopt_node.h"

int main(int argc, char** argv) {
  fesd::keepLargeAllocationsInTheHeap();  // each request ends with releaseFreeMemory()
  ros::init(argc, argv, "fesd_trajopt");
  ros::NodeHandle node, private_node("~");
  try {
    fesd_ros::TrajoptNode trajopt(node, private_node);
    // Requests are served concurrently, each with its own solver state.
    ros::AsyncSpinner spinner(trajopt.solverThreads());
    spinner.start();
    ros::waitForShutdown();
  } catch (const std::exception& error) {
    ROS_FATAL_STREAM("fesd_trajopt: " << error.what());
    return 1;
  }
  return 0;
}
