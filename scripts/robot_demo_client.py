#!/usr/bin/python3
"""Asks a running fesd_trajopt node, started on the planar arm (launch/robot_demo.launch), to push
a disc with the arm, and prints a summary.

The shipped push (scene/robot_scenes.h): the arm from shoulder = -0.6 rad pushes a disc of radius
0.05 m from (0.6, 0) to (0.6, 0.2) in 2 s on 10 control intervals.
Usage: rosrun fesd_trajopt robot_demo_client.py
"""
import sys

import rospy
from fesd_trajopt.msg import BodySpec, JointSpec, PlanRequest, Solution, SwitchEvent
from fesd_trajopt.srv import SolveTrajectory
from geometry_msgs.msg import Point

STATUS = {getattr(Solution, name): name for name in dir(Solution)
          if name.isupper() and isinstance(getattr(Solution, name), int)}


def main():
    rospy.init_node("fesd_trajopt_robot_demo_client", anonymous=True)
    rospy.wait_for_service("/fesd_trajopt/solve_trajectory", timeout=60.0)
    solve = rospy.ServiceProxy("/fesd_trajopt/solve_trajectory", SolveTrajectory)
    request = PlanRequest()  # the node's ~scene_urdf: the arm
    request.bodies = [BodySpec(name="disc", add=True, radius=0.05,
                               initial_position=Point(0.6, 0.0, 0.0),
                               target=Point(0.6, 0.2, 0.0), target_weight=100.0)]
    request.joints = [JointSpec(name="shoulder", has_initial_position=True, initial_position=-0.6)]
    request.has_horizon, request.horizon = True, 2.0
    request.has_num_intervals, request.num_intervals = True, 10
    request.has_num_elements, request.num_elements = True, 2
    request.contact_pairs = PlanRequest.PAIRS_ALL_IN_REACH
    started = rospy.Time.now()
    response = solve(request)
    round_trip = (rospy.Time.now() - started).to_sec()
    solution = response.solution
    print("fesd_trajopt robot demo: %s (%d)" % (STATUS.get(response.status, "?"), response.status))
    print("  %s" % response.message)
    disc = solution.bodies[0]
    print("  disc (%.3f, %.3f) -> (%.3f, %.3f)" % (disc.positions[0].x, disc.positions[0].y,
                                                   disc.positions[-1].x, disc.positions[-1].y))
    motion = solution.joint_trajectory
    print("  joints %s: %s -> %s" % (
        ", ".join(motion.joint_names), ["%.3f" % q for q in motion.points[0].positions],
        ["%.3f" % q for q in motion.points[-1].positions]))
    for event in solution.switches:
        kind = "contact" if event.kind == SwitchEvent.CONTACT else "release"
        print("  %-7s %s/%s at t = %.4f" % (kind, event.first, event.second, event.time))
    print("  solve %.2f s; round trip %.2f s" % (solution.statistics.wall_time, round_trip))
    return 0 if response.status == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
