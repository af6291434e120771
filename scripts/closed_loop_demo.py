#!/usr/bin/python3
"""Executes a plan with feedback: replans every few intervals from the state reached, warm.

A plan whose answer says needs_feedback (a push by one pusher: open loop, a tiny error at the start
of the push grows by orders of magnitude) is executed here as a robot would: its controls are
applied for --every intervals (through ~simulate on a fine grid, standing in for the robot), then
~solve_trajectory is asked for the fastest answer (target_accuracy -1) over the rest of the
horizon from the state reached, with warm_start, which starts from the rest of the last plan.
Prints each replan and where the pushed body ends, with feedback and without.

Usage: rosrun fesd_trajopt closed_loop_demo.py [--every 3] [--scene push|default]
"""
import argparse
import copy
import math
import sys

import rospy
from geometry_msgs.msg import Point, Vector3

from fesd_trajopt.msg import BodySpec, BodyTrajectory, PlanRequest, Solution
from fesd_trajopt.srv import Simulate, SimulateRequest, SolveTrajectory

STATUS = {getattr(Solution, name): name for name in dir(Solution)
          if name.isupper() and isinstance(getattr(Solution, name), int)}
EMPTY = '<robot name="empty"><link name="world"/></robot>'


def scene(name):
    """(request, pushed body's name, its target) of a scene."""
    request = PlanRequest()
    if name == "push":  # one pusher takes a puck 5.8 diagonally in 5 s: open-loop unstable
        target = Point(5.0, 3.0, 0.0)
        request.urdf = EMPTY
        request.bodies = [
            BodySpec(name="pusher", add=True, radius=0.5, initial_position=Point(-2.0, 0.0, 0.0),
                     role=BodySpec.ROLE_ACTUATED, max_speed=4.0),
            BodySpec(name="puck", add=True, radius=0.5, initial_position=Point(0.0, 0.0, 0.0),
                     target=target, target_weight=100.0)]
        request.has_horizon, request.horizon = True, 5.0
        request.has_num_intervals, request.num_intervals = True, 40
        return request, "puck", target
    return request, "object", Point(0.0, 10.0, 0.0)


def placed(request, positions):
    """The request with its bodies each at its position in `positions` (name -> Point)."""
    request = copy.deepcopy(request)
    bodies = {b.name: b for b in request.bodies}
    for name, position in positions.items():
        spec = bodies.setdefault(name, BodySpec(name=name))
        spec.initial_position, spec.override_initial_position = position, True
    request.bodies = list(bodies.values())
    return request


def simulate(service, request, positions, solution, first, steps):
    """The plant: the solution's controls of intervals first .. first + steps from `positions`
    on a fine grid; the bodies' positions at the end."""
    plant = SimulateRequest()
    plant.urdf, plant.urdf_param = request.urdf, request.urdf_param
    plant.bodies = placed(PlanRequest(bodies=list(request.bodies)), positions).bodies
    plant.obstacles, plant.walls = request.obstacles, request.walls
    for body in solution.bodies:
        if body.actuated:
            plant.commands.append(BodyTrajectory(
                name=body.name, controls=[Vector3(u.x, u.y, u.z)
                                          for u in body.controls[first:first + steps]]))
    interval = solution.control_times[1] - solution.control_times[0]
    plant.has_horizon, plant.horizon = True, steps * interval
    plant.has_num_steps, plant.num_steps = True, steps
    plant.has_num_elements, plant.num_elements = True, 6
    plant.has_num_stages, plant.num_stages = True, 3
    answer = service(plant)
    if answer.status != Solution.SUCCESS:
        raise RuntimeError("the plant's simulation failed: " + answer.message)
    return {b.name: b.positions[-1] for b in answer.solution.bodies}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--every", type=int, default=3, help="intervals between replans")
    parser.add_argument("--scene", choices=["push", "default"], default="push")
    args = parser.parse_args(rospy.myargv()[1:])
    rospy.init_node("fesd_trajopt_closed_loop_demo", anonymous=True)
    rospy.wait_for_service("/fesd_trajopt/solve_trajectory", timeout=60.0)
    rospy.wait_for_service("/fesd_trajopt/simulate", timeout=60.0)
    solve = rospy.ServiceProxy("/fesd_trajopt/solve_trajectory", SolveTrajectory)
    plant = rospy.ServiceProxy("/fesd_trajopt/simulate", Simulate)
    request, pushed, target = scene(args.scene)
    first = solve(request)
    plan = first.solution
    if first.status not in (Solution.SUCCESS, Solution.ACCURACY_NOT_MET):
        print("the first plan: %s: %s" % (STATUS.get(first.status, "?"), first.message))
        return 1
    print("first plan: %s in %.3f s, verification error %.2g, open loop error %.2g (gain %.3g)%s"
          % (STATUS[first.status], plan.statistics.wall_time, plan.verification_error,
             plan.open_loop_error, plan.open_loop_gain,
             ", needs feedback" if plan.needs_feedback else ""))
    start = {b.name: b.positions[0] for b in plan.bodies}
    intervals = len(plan.control_times) - 1
    interval = plan.control_times[1] - plan.control_times[0]
    open_loop = simulate(plant, request, start, plan, 0, intervals)
    positions, used, done, replan_time = start, 0, 0, 0.0
    while done < intervals:
        steps = min(args.every, intervals - done)
        positions = simulate(plant, request, positions, plan, used, steps)
        done, used = done + steps, used + steps
        if done == intervals:
            break
        replan = placed(scene(args.scene)[0], positions)
        replan.target_accuracy, replan.warm_start = -1.0, True
        replan.has_horizon, replan.horizon = True, (intervals - done) * interval
        replan.has_num_intervals, replan.num_intervals = True, intervals - done
        answer = solve(replan)
        stats = answer.solution.statistics
        replan_time += stats.wall_time
        print("  after %2d intervals: %-8s %-5s %3d Ipopt iterations %6.3f s  (%s)" % (
            done, STATUS.get(answer.status, "?"), "warm" if stats.warm_started else "cold",
            stats.ipopt_iterations, stats.wall_time, stats.start))
        if answer.status in (Solution.SUCCESS, Solution.TARGET_NOT_REACHED):
            plan, used = answer.solution, 0
    miss = lambda p: math.hypot(p.x - target.x, p.y - target.y)
    closed = miss(positions[pushed])
    print("%s ends %.3g from its target with feedback, %.3g without; replans %.3f s in all "
          "(%.2fx the first plan)" % (pushed, closed, miss(open_loop[pushed]), replan_time,
                                      replan_time / plan_time(first)))
    return 0 if closed <= 1e-2 else 1


def plan_time(answer):
    return max(answer.solution.statistics.wall_time, 1e-9)


if __name__ == "__main__":
    sys.exit(main())
