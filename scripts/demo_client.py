#!/usr/bin/python3
"""Calls ~solve_trajectory of a running fesd_trajopt node and prints a summary.

The Python usage example: an empty request solves the default scene; see --help for a few
overrides. Usage: rosrun fesd_trajopt demo_client.py [--intervals N] [--elements N] [--verify]
[--obstacle X Y R ...] [--push-t X Y YAW PUSHER_X PUSHER_Y]
"""
import argparse
import math
import sys

import rospy
from geometry_msgs.msg import Point

from fesd_trajopt.msg import BodySpec, Obstacle, PlanRequest, Solution, SwitchEvent
from fesd_trajopt.srv import SolveTrajectory

# Status code -> name, from Solution.msg's constants.
STATUS = {getattr(Solution, name): name for name in dir(Solution)
          if name.isupper() and isinstance(getattr(Solution, name), int)}


def push_t(request, x, y, yaw, pusher_x, pusher_y):
    """Push-T (examples/push_t.h): a T of width 0.5 (a bar of 7 spheres over a stem of 5) at
    (x, y, yaw) about its centre of pressure, one disc pusher, the target pose (0, 0, pi / 4)
    taken at the yaw equivalent nearest the start; 10 s in 40 intervals."""
    request.urdf = '<robot name="table"><link name="world"/></robot>'
    offsets = [Point(x=0.25 * k) for k in range(-3, 4)] + [Point(y=-0.25 * k) for k in range(2, 7)]
    target_yaw = yaw + math.remainder(math.pi / 4 - yaw, 2 * math.pi)
    request.bodies = [
        BodySpec(name="pusher", add=True, radius=0.25, initial_position=Point(x=pusher_x, y=pusher_y),
                 role=BodySpec.ROLE_ACTUATED, max_speed=2.0),
        BodySpec(name="t_block", add=True, turns=True, initial_position=Point(x=x, y=y),
                 initial_yaw=yaw, sphere_offsets=offsets, sphere_radii=[0.25] * len(offsets),
                 target=Point(), target_weight=100.0, target_yaw=target_yaw,
                 target_yaw_weight=100.0)]
    request.has_horizon, request.horizon = True, 10.0
    request.has_num_intervals, request.num_intervals = True, 40


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--service", default="/fesd_trajopt/solve_trajectory")
    parser.add_argument("--intervals", type=int, help="control intervals (default: configured)")
    parser.add_argument("--elements", type=int, help="finite elements per interval")
    parser.add_argument("--verify", action="store_true", help="re-simulate on a finer grid")
    parser.add_argument("--obstacle", type=float, nargs=3, action="append", default=[],
                        metavar=("X", "Y", "R"), help="a fixed disc added to the scene")
    parser.add_argument("--push-t", type=float, nargs=5,
                        metavar=("X", "Y", "YAW", "PUSHER_X", "PUSHER_Y"),
                        help="Push-T instead of the default scene: the T's start and the pusher's")
    args = parser.parse_args(rospy.myargv()[1:])
    rospy.init_node("fesd_trajopt_demo_client", anonymous=True)
    rospy.wait_for_service(args.service, timeout=60.0)
    solve = rospy.ServiceProxy(args.service, SolveTrajectory)
    request = PlanRequest()
    if args.push_t:
        push_t(request, *args.push_t)
    if args.intervals:
        request.has_num_intervals, request.num_intervals = True, args.intervals
    if args.elements:
        request.has_num_elements, request.num_elements = True, args.elements
    request.verify = args.verify
    for k, (x, y, radius) in enumerate(args.obstacle):
        request.obstacles.append(Obstacle(name="post_%d" % k, radius=radius,
                                          position=Point(x=x, y=y)))
    started = rospy.Time.now()
    response = solve(request)
    round_trip = (rospy.Time.now() - started).to_sec()
    solution = response.solution
    print("fesd_trajopt demo: %s (%d)" % (STATUS.get(response.status, "?"), response.status))
    print("  %s" % response.message)
    for body in solution.bodies:
        start, end = body.positions[0], body.positions[-1]
        print("  %-12s %-8s (%7.3f, %7.3f) -> (%7.3f, %7.3f)%s" % (
            body.name, "actuated" if body.actuated else "passive", start.x, start.y, end.x, end.y,
            ", yaw %.3f -> %.3f" % (body.yaws[0], body.yaws[-1]) if body.yaws else ""))
    for event in solution.switches:
        kind = "contact" if event.kind == SwitchEvent.CONTACT else "release"
        print("  %-7s %s/%s at t = %.4f" % (kind, event.first, event.second, event.time))
    for pair in solution.checked_pairs:
        print("  checked %s/%s: %s" % (pair.first, pair.second, pair.reason))
    for pair in solution.pruned_pairs:
        print("  pruned  %s/%s: %s" % (pair.first, pair.second, pair.reason))
    stats = solution.statistics
    print("  %d Ipopt iterations in %d homotopy steps, residual %.1e, objective %.6g" % (
        stats.ipopt_iterations, stats.homotopy_steps, stats.complementarity_residual,
        stats.objective))
    print("  first guess (%s): residual %.3g in the NLP's equations" % (
        stats.start, stats.guess_residual))
    print("  solve %.2f s (Ipopt %.2f s, evaluations %.2f s); round trip %.2f s" % (
        stats.wall_time, stats.ipopt_time, stats.evaluation_time, round_trip))
    if solution.verified:
        print("  re-simulated on a finer grid interval by interval: largest error %.3g; open loop "
              "the end deviates by %.3g (a deviation grows up to %.3g-fold)%s" % (
                  solution.verification_error, solution.open_loop_error,
                  solution.open_loop_gain,
                  ": execute with feedback" if solution.needs_feedback else ""))
        for graze in solution.grazes:
            print("  graze %s/%s at t = %.4f: the plan's gap %.3g%s" % (
                graze.pair.first, graze.pair.second, graze.time, graze.depth,
                ", touched in the re-simulation" if graze.touched else ""))
    for rung in solution.refinements[1:]:
        print("  rung: %s (%s): error %.3g -> %.3g in %.2f s%s" % (
            rung.change, rung.reason, rung.error_before, rung.verification_error, rung.wall_time,
            "" if rung.from_previous_plan else ", cold"))
    return 0 if response.status == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
