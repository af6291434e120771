#!/usr/bin/python3
"""Replans the default scene while its object's target moves, warm-starting each plan from the last.

Moves the object's target (0, 10) along x in --steps steps of --step, calls ~solve_trajectory
with warm_start = true after each move and prints the time of each replan; then solves the last
target cold for comparison. Usage: rosrun fesd_trajopt replan_demo.py [--steps 10] [--step 0.03]
"""
import argparse
import sys

import rospy
from fesd_trajopt.msg import BodySpec, PlanRequest, Solution
from fesd_trajopt.srv import SolveTrajectory
from geometry_msgs.msg import Point


def request_for(target_x, warm_start):
    request = PlanRequest(warm_start=warm_start)
    request.bodies = [BodySpec(name="object", target=Point(target_x, 10.0, 0.0),
                               target_weight=1000.0)]
    return request


def report(label, target_x, response):
    statistics = response.solution.statistics
    print("%-6s target x = %5.2f  %-8s %-5s %3d Ipopt iterations  %6.3f s" % (
        label, target_x, "SUCCESS" if response.status == Solution.SUCCESS else response.status,
        "warm" if statistics.warm_started else "cold", statistics.ipopt_iterations,
        statistics.wall_time))
    return statistics.wall_time


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--service", default="/fesd_trajopt/solve_trajectory")
    parser.add_argument("--steps", type=int, default=10)
    parser.add_argument("--step", type=float, default=0.03, help="target move per step")
    args = parser.parse_args(rospy.myargv()[1:])
    rospy.init_node("fesd_trajopt_replan_demo", anonymous=True)
    rospy.wait_for_service(args.service, timeout=60.0)
    solve = rospy.ServiceProxy(args.service, SolveTrajectory)
    report("start", 0.0, solve(request_for(0.0, False)))
    replans, ok = [], True
    for step in range(1, args.steps + 1):
        target_x = step * args.step
        response = solve(request_for(target_x, True))
        replans.append(report("replan", target_x, response))
        ok = ok and response.status == Solution.SUCCESS
    cold = report("cold", target_x, solve(request_for(target_x, False)))
    replans.sort()
    median = replans[len(replans) // 2]
    print("median replan %.3f s = %.0f %% of the cold solve (%.3f s)" % (
        median, 100.0 * median / cold, cold))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
