#!/usr/bin/python3
"""The node under load: several clients at once, hundreds of mixed requests (plans of disc and
robot scenes, simulations, action goals, broken requests). Every answer must equal the one the
same request gets alone, and the node must serve on afterwards."""
import random
import threading
import unittest

import actionlib
import rospy
import rostest
from fesd_trajopt.msg import (BodySpec, BodyTrajectory, JointSpec, PlanRequest,
                              PlanTrajectoryAction, PlanTrajectoryGoal, Solution)
from fesd_trajopt.srv import Simulate, SimulateRequest, SolveTrajectory
from geometry_msgs.msg import Point, Vector3

SOLVE = "/fesd_trajopt/solve_trajectory"
SIMULATE = "/fesd_trajopt/simulate"
PLAN = "/fesd_trajopt/plan"
CLIENTS = 4
REQUESTS_PER_CLIENT = 50


def small_default(intervals):
    request = PlanRequest()
    request.has_num_intervals, request.num_intervals = True, intervals
    request.has_num_elements, request.num_elements = True, 2
    return request


def moved_object(x):
    request = small_default(12)
    request.bodies = [BodySpec(name="object", target=Point(x, 10.0, 0.0), target_weight=1000.0)]
    return request


def arm_push():
    request = PlanRequest()
    request.urdf_param = "/planar_arm"
    request.bodies = [BodySpec(name="disc", add=True, radius=0.05,
                               initial_position=Point(0.6, 0.0, 0.0), role=BodySpec.ROLE_PASSIVE,
                               target=Point(0.6, 0.2, 0.0), target_weight=100.0)]
    request.joints = [JointSpec(name="shoulder", has_initial_position=True, initial_position=-0.6)]
    request.has_horizon, request.horizon = True, 2.0
    request.has_num_intervals, request.num_intervals = True, 10
    request.has_num_elements, request.num_elements = True, 2
    return request


def broken():
    request = small_default(10)
    request.has_num_elements, request.num_elements = True, 99
    return request


def circle():
    request = SimulateRequest(system="circle_example")
    request.has_num_steps, request.num_steps = True, 8
    return request


def scene_simulation():
    request = SimulateRequest()
    request.commands = [BodyTrajectory(name="actuator_2", controls=[Vector3(-1.0, 1.0, 0.0)])]
    request.has_horizon, request.horizon = True, 4.0
    request.has_num_steps, request.num_steps = True, 8
    return request


# Kind -> (service, request factory). Warm starts are left out: their answer depends on which
# plan finished last, which concurrency makes arbitrary.
PLANS = {"default_10": lambda: small_default(10), "default_14": lambda: small_default(14),
         "default": PlanRequest, "object_x_0.2": lambda: moved_object(0.2),
         "object_x_-0.3": lambda: moved_object(-0.3), "arm_push": arm_push, "broken": broken}
SIMULATIONS = {"circle": circle, "scene_simulation": scene_simulation}


def fingerprint(solution, status):
    """What must be identical between two answers to one request (no timings)."""
    return (status, solution.statistics.ipopt_iterations, solution.statistics.objective,
            tuple(solution.times), tuple(solution.states),
            tuple((s.first, s.second, s.kind, s.time) for s in solution.switches),
            solution.verification_error if solution.verified else None)


class NodeUnderLoad(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("fesd_trajopt_load_test")
        rospy.wait_for_service(SOLVE, timeout=60.0)
        rospy.wait_for_service(SIMULATE, timeout=60.0)
        solve = rospy.ServiceProxy(SOLVE, SolveTrajectory)
        simulate = rospy.ServiceProxy(SIMULATE, Simulate)
        cls.alone = {}
        for kind, make in PLANS.items():
            response = solve(make())
            cls.alone[kind] = fingerprint(response.solution, response.status)
        for kind, make in SIMULATIONS.items():
            response = simulate(make())
            cls.alone[kind] = fingerprint(response.solution, response.status)

    def test_references_are_what_each_request_asks_for(self):
        for kind in PLANS:
            expected = Solution.INVALID_REQUEST if kind == "broken" else Solution.SUCCESS
            self.assertEqual(self.alone[kind][0], expected, kind)
        for kind in SIMULATIONS:
            self.assertEqual(self.alone[kind][0], Solution.SUCCESS, kind)

    def test_clients_at_once_get_the_answers_of_requests_alone(self):
        mismatches, errors, answered = [], [], [0]
        lock = threading.Lock()

        def client(index):
            rng = random.Random(index)
            solve = rospy.ServiceProxy(SOLVE, SolveTrajectory)
            simulate = rospy.ServiceProxy(SIMULATE, Simulate)
            action = actionlib.SimpleActionClient(PLAN, PlanTrajectoryAction)
            action.wait_for_server(rospy.Duration(30.0))
            kinds = list(PLANS) + list(SIMULATIONS)
            for _ in range(REQUESTS_PER_CLIENT):
                kind = rng.choice(kinds)
                try:
                    if kind in SIMULATIONS:
                        response = simulate(SIMULATIONS[kind]())
                        got = fingerprint(response.solution, response.status)
                    elif index == 0 and kind != "broken":  # one client sends action goals
                        action.send_goal(PlanTrajectoryGoal(request=PLANS[kind]()))
                        action.wait_for_result(rospy.Duration(300.0))
                        result = action.get_result()
                        got = fingerprint(result.solution, result.status)
                    else:
                        response = solve(PLANS[kind]())
                        got = fingerprint(response.solution, response.status)
                except Exception as error:  # a dead node: the call fails
                    with lock:
                        errors.append("%s: %s" % (kind, error))
                    continue
                with lock:
                    answered[0] += 1
                    if got != self.alone[kind]:
                        mismatches.append(kind)

        threads = [threading.Thread(target=client, args=(i,)) for i in range(CLIENTS)]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join(timeout=1200.0)
        self.assertEqual(errors, [])
        self.assertEqual(answered[0], CLIENTS * REQUESTS_PER_CLIENT)
        self.assertEqual(mismatches, [])
        # Alive and serving afterwards.
        response = rospy.ServiceProxy(SOLVE, SolveTrajectory)(small_default(10))
        self.assertEqual(fingerprint(response.solution, response.status), self.alone["default_10"])


if __name__ == "__main__":
    rostest.rosrun("fesd_trajopt", "load", NodeUnderLoad)
