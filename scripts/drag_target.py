#!/usr/bin/python3
"""Drags a body's target as rviz does: publishes a release (MOUSE_UP) of its interactive marker at
(x, y) and prints the solution the node publishes for it.

Usage: rosrun fesd_trajopt drag_target.py object 0.4 7.0
"""
import argparse
import sys
import threading

import rospy
from fesd_trajopt.msg import Solution
from visualization_msgs.msg import InteractiveMarkerFeedback

STATUS = {getattr(Solution, name): name for name in dir(Solution)
          if name.isupper() and isinstance(getattr(Solution, name), int)}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("body")
    parser.add_argument("x", type=float)
    parser.add_argument("y", type=float)
    parser.add_argument("--frame", default="world", help="the node's ~frame_id")
    parser.add_argument("--timeout", type=float, default=120.0, help="seconds to wait")
    args = parser.parse_args(rospy.myargv()[1:])
    rospy.init_node("fesd_trajopt_drag_target", anonymous=True)
    released = threading.Event()
    answered = []

    def received(solution):
        if released.is_set():  # not the latched solution from before
            answered.append(solution)

    rospy.Subscriber("/fesd_trajopt/solution", Solution, received)
    feedback = rospy.Publisher("/fesd_trajopt/targets/feedback", InteractiveMarkerFeedback,
                               queue_size=1)
    deadline = rospy.Time.now() + rospy.Duration(args.timeout)
    while feedback.get_num_connections() == 0 and rospy.Time.now() < deadline:
        rospy.sleep(0.05)
    rospy.sleep(0.5)  # the latched solution first
    release = InteractiveMarkerFeedback(client_id="/drag_target", marker_name=args.body,
                                        event_type=InteractiveMarkerFeedback.MOUSE_UP)
    release.header.frame_id = args.frame
    release.pose.position.x, release.pose.position.y = args.x, args.y
    release.pose.orientation.w = 1.0
    released.set()
    feedback.publish(release)
    while not answered and rospy.Time.now() < deadline and not rospy.is_shutdown():
        rospy.sleep(0.05)
    if not answered:
        print("no solution within %.0f s (an unknown body or a refused pose: see the node's log)"
              % args.timeout)
        return 1
    solution = answered[0]
    (body,) = [b for b in solution.bodies if b.name == args.body] or [None]
    end = body.positions[-1] if body else None
    print("%s: %s in %.3f s (%s), %s ends at (%.4f, %.4f)" % (
        args.body, STATUS.get(solution.status, "?"), solution.statistics.wall_time,
        "warm" if solution.statistics.warm_started else "cold", args.body,
        end.x if end else float("nan"), end.y if end else float("nan")))
    return 0 if solution.status == Solution.SUCCESS else 1


if __name__ == "__main__":
    sys.exit(main())
