#!/usr/bin/python3
"""Steers a pushed puck to a target by gradient steps on the pusher's commands, through ~simulate.

The sensitivities example: a pusher (actuated) and a puck, the pusher commanded a velocity per
step; each iteration simulates with sensitivities = true and moves the commands against the
gradient of |puck(T) - target|^2, d puck(T) / d u read from state_by_controls. The derivatives are
exact across the contact, so the steps know how the contact's time and angle move with u.
Usage: rosrun fesd_trajopt gradient_step_demo.py [--iterations N] [--target X Y] [--step S]
Exits 1 if the cost did not fall.
"""
import argparse
import sys

import numpy as np
import rospy
from geometry_msgs.msg import Point, Vector3

from fesd_trajopt.msg import BodySpec, BodyTrajectory, Solution
from fesd_trajopt.srv import Simulate, SimulateRequest

STEPS, HORIZON = 8, 2.0


def push_request(commands):
    """The pusher at (-2, 0.2) behind the puck at the origin, `commands` (STEPS x 2) per step."""
    request = SimulateRequest(sensitivities=True)
    request.urdf = '<robot name="empty"><link name="world"/></robot>'
    request.bodies = [
        BodySpec(name="pusher", add=True, radius=0.5, initial_position=Point(-2.0, 0.2, 0.0),
                 role=BodySpec.ROLE_ACTUATED),
        BodySpec(name="puck", add=True, radius=0.5, initial_position=Point(0.0, 0.0, 0.0))]
    request.commands = [BodyTrajectory(name="pusher",
                                       controls=[Vector3(u[0], u[1], 0.0) for u in commands])]
    request.has_horizon, request.horizon = True, HORIZON
    request.has_num_steps, request.num_steps = True, STEPS
    return request


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--service", default="/fesd_trajopt/simulate")
    parser.add_argument("--iterations", type=int, default=10)
    parser.add_argument("--target", type=float, nargs=2, default=[1.0, 0.4])
    parser.add_argument("--step", type=float, default=0.2, help="gradient step size")
    args = parser.parse_args(rospy.myargv()[1:])
    rospy.init_node("fesd_trajopt_gradient_step_demo", anonymous=True)
    rospy.wait_for_service(args.service, timeout=60.0)
    simulate = rospy.ServiceProxy(args.service, Simulate)
    target = np.array(args.target)
    commands = np.tile([1.5, 0.0], (STEPS, 1))
    costs = []
    for iteration in range(args.iterations):
        response = simulate(push_request(commands))
        sensitivities = response.sensitivities
        if response.status != Solution.SUCCESS or not sensitivities.all_defined:
            print("iteration %d: %s %s" % (iteration, response.message,
                                           sensitivities.undefined_reason))
            return 1
        names = sensitivities.state_names
        puck = [names.index("puck/x"), names.index("puck/y")]
        final = np.array(response.solution.states[-len(names):])[puck]
        # d x(t_N) / d u: the last step's block, rows = states, columns = (step, control).
        by_controls = np.array(sensitivities.state_by_controls.data).reshape(
            [d.size for d in sensitivities.state_by_controls.layout.dim])[-1]
        gradient = 2.0 * (final - target) @ by_controls[puck]
        costs.append(float(np.sum((final - target) ** 2)))
        print("iteration %d: puck at (%.3f, %.3f), cost %.5f, %d switch(es)" %
              (iteration, final[0], final[1], costs[-1], len(response.solution.switches)))
        commands -= args.step * gradient.reshape(STEPS, 2)
    return 0 if costs[-1] < costs[0] else 1


if __name__ == "__main__":
    sys.exit(main())
