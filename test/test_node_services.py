#!/usr/bin/python3
"""Integration tests of the fesd_trajopt node: services, statuses, markers, concurrency."""
import math
import os
import random
import subprocess
import threading
import unittest

import rospy
import rostest
import tf2_ros
from fesd_trajopt.msg import (BodySpec, BodyTrajectory, ContactPair, Obstacle, PlanRequest, Solution,
                              SwitchEvent, Wall)
from fesd_trajopt.srv import Simulate, SimulateRequest, SolveTrajectory
from geometry_msgs.msg import Point, Vector3
from nav_msgs.msg import Path
from visualization_msgs.msg import MarkerArray

SUCCESS, INFEASIBLE, TIMEOUT, INVALID_REQUEST = (Solution.SUCCESS, Solution.INFEASIBLE,
                                            Solution.TIMEOUT, Solution.INVALID_REQUEST)
# A service call is never cancelled (only a ~plan goal is); every other status is a valid answer.
ALL_STATUSES_BUT_CANCELLED = [s for s in range(Solution.TARGET_NOT_REACHED + 1) if s != Solution.CANCELLED]
SOLVE = "/fesd_trajopt/solve_trajectory"
SIMULATE = "/fesd_trajopt/simulate"


def chain_urdf(links):
    """A serial chain of revolute joints, each link with a sphere (2.5 MB for 20000 links)."""
    parts = ['<robot name="chain"><link name="l0"/>']
    for i in range(1, links):
        parts.append('<link name="l%d"><collision><geometry><sphere radius="0.1"/></geometry>'
                     '</collision></link><joint name="j%d" type="continuous"><parent link="l%d"/>'
                     '<child link="l%d"/><origin xyz="1 0 0"/><axis xyz="0 0 1"/></joint>'
                     % (i, i, i - 1, i))
    parts.append("</robot>")
    return "".join(parts)


def body(name, **fields):
    spec = BodySpec(name=name)
    for key, value in fields.items():
        setattr(spec, key, value)
    return spec


def small_default(intervals=10):
    """The default scene on a coarse grid: a quick but complete solve."""
    request = PlanRequest()
    request.has_num_intervals, request.num_intervals = True, intervals
    request.has_num_elements, request.num_elements = True, 2
    return request


def three_disc_request(target_x, intervals):
    """The three-disc URDF scene: the pusher drives the puck to (target_x, 0) in 2 s."""
    request = PlanRequest()
    request.urdf_param = "/three_disc_scene"
    request.bodies = [body("pusher", role=BodySpec.ROLE_ACTUATED, max_speed=3.0),
                      body("puck", target=Point(target_x, 0, 0), target_weight=10.0)]
    request.has_horizon, request.horizon = True, 2.0
    request.has_num_intervals, request.num_intervals = True, intervals
    return request


def random_request(rng):
    """A request with random, often broken fields, kept small enough to solve quickly."""
    nasty = [0.0, -1.0, 1e-300, 1e300, float("inf"), -float("inf"), float("nan")]

    def number(low, high):
        return rng.uniform(low, high) if rng.random() < 0.8 else rng.choice(nasty)

    def point():
        return Point(number(-15, 15), number(-15, 15), number(-1, 1))

    names = ["actuator_1", "actuator_2", "object", "extra", ""]
    request = PlanRequest()
    for _ in range(rng.randint(0, 3)):
        spec = body(rng.choice(names), add=rng.random() < 0.3, radius=number(0.1, 2.0),
                    initial_position=point(), override_initial_position=rng.random() < 0.3,
                    role=rng.randint(0, 3), max_speed=number(0, 10), target=point(),
                    target_weight=number(0, 10) if rng.random() < 0.5 else 0.0,
                    clear_target=rng.random() < 0.2)
        spec.workspace_lower = [number(-20, 0) for _ in range(rng.choice([0, 2, 2, 3]))]
        spec.workspace_upper = [number(0, 20) for _ in range(rng.choice([0, 2, 2, 3]))]
        request.bodies.append(spec)
    for i in range(rng.randint(0, 1)):
        request.obstacles.append(Obstacle(name="o%d" % i, radius=number(0.1, 1), position=point()))
    for i in range(rng.randint(0, 1)):
        request.walls.append(Wall(name="w%d" % i, normal=Vector3(number(-1, 1), number(-1, 1), 0),
                                  offset=number(-30, -20)))
    if rng.random() < 0.2:
        request.allowed_pairs = [ContactPair(first=rng.choice(names), second=rng.choice(names))]
    request.has_horizon, request.horizon = rng.random() < 0.5, number(0.5, 3.0)
    request.has_num_intervals, request.num_intervals = True, rng.choice([0, 1, 2, 3])
    request.has_num_elements, request.num_elements = True, rng.choice([0, 1, 2, 9])
    request.method = rng.choice([0, 1, 2, 7])
    request.has_wall_time_budget, request.wall_time_budget = True, number(0.5, 1.0)
    request.warm_start = rng.random() < 0.5
    request.target_accuracy = rng.choice([0.0, 0.0, -1.0, 1e-3, number(0.0, 1e-2),
                                          float("nan"), float("inf")])
    return request


def random_simulate_request(rng):
    """A Simulate request with random, often broken commands and sizes."""
    nasty = [0.0, 1e300, float("inf"), float("nan")]
    request = SimulateRequest(system=rng.choice(["", "", "circle_example", "pendulum", "spiral"]),
                              sensitivities=rng.random() < 0.5)
    request.urdf_param = "/three_disc_scene"
    request.bodies = [body("pusher", role=rng.choice([0, 1, 2]))]
    for _ in range(rng.randint(0, 2)):
        controls = [Vector3(rng.choice([rng.uniform(-3, 3)] * 3 + nasty), rng.uniform(-3, 3), 0)
                    for _ in range(rng.choice([0, 1, 2, 3]))]
        request.commands.append(BodyTrajectory(name=rng.choice(["pusher", "puck", "x"]),
                                               controls=controls))
    request.has_horizon, request.horizon = rng.random() < 0.7, rng.choice([0.5, 1.0, -1.0, 1e9])
    request.has_num_steps, request.num_steps = True, rng.choice([0, 1, 2, 3, 100000])
    request.has_num_elements, request.num_elements = rng.random() < 0.5, rng.choice([0, 1, 2])
    request.has_wall_time_budget, request.wall_time_budget = True, rng.choice([5.0, 0.0, 1e-3])
    return request


class NodeServices(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("fesd_trajopt_node_test")
        rospy.wait_for_service(SOLVE, timeout=60.0)
        rospy.wait_for_service(SIMULATE, timeout=60.0)
        cls.solve = rospy.ServiceProxy(SOLVE, SolveTrajectory)
        cls.simulate = rospy.ServiceProxy(SIMULATE, Simulate)
        cls.default = cls.solve(PlanRequest())

    def assert_invalid(self, request, keyword):
        response = self.solve(request)
        self.assertEqual(response.status, INVALID_REQUEST, keyword + ": " + response.message)
        self.assertIn(keyword, response.message)

    def test_empty_request_solves_the_default_scene(self):
        response = self.default
        self.assertEqual(response.status, SUCCESS, response.message)
        kinds = [event.kind for event in response.solution.switches]
        self.assertIn(SwitchEvent.CONTACT, kinds)
        self.assertIn(SwitchEvent.RELEASE, kinds)
        final = {b.name: b.positions[-1] for b in response.solution.bodies}
        self.assertLess(math.hypot(final["object"].x, final["object"].y - 10.0), 0.1)
        statistics = response.solution.statistics
        self.assertLessEqual(statistics.complementarity_residual, 1e-8)
        # The answer is certified B-stationary by an LPEC at it (no pair near a switch here: the
        # branch NLP's KKT point is the certificate, value 0).
        self.assertEqual(statistics.mpcc_method, "homotopy")
        self.assertTrue(statistics.certified, statistics.certificate)
        self.assertEqual(statistics.lpec_value, 0.0)
        self.assertEqual(statistics.lpec_radius, 1e-3)
        self.assertGreaterEqual(statistics.lpecs, 1)
        self.assertEqual(statistics.relaxed_nlps + statistics.branch_nlps, statistics.homotopy_steps)
        modeled = {(p.first, p.second) for p in response.solution.modeled_pairs}
        self.assertEqual(modeled, {("actuator_1", "object"), ("actuator_2", "object")})
        self.assertEqual([(p.first, p.second) for p in response.solution.pruned_pairs],
                         [("actuator_1", "actuator_2")])
        for b in response.solution.bodies:  # workspace bounds at every element boundary
            if b.name == "actuator_1":
                self.assertTrue(all(p.x <= -2.5 + 1e-6 for p in b.positions))
            if b.name == "actuator_2":
                self.assertTrue(all(p.x >= 2.5 - 1e-6 for p in b.positions))
        self.assertEqual(len(response.solution.times), len(response.solution.step_lengths) + 1)

    def test_the_default_scene_at_desk_size_is_the_same_plan_in_metres(self):
        """Every length of the default scene times 0.01 (a 4 cm disc pushed 10 cm), given in the
        request: solved in units of its length scale, the same plan scaled, answered in metres."""
        k = 0.01
        request = PlanRequest()
        request.urdf = '<robot name="empty"><link name="world"/></robot>'
        inf = float("inf")
        request.bodies = [
            body("actuator_1", add=True, radius=1.0 * k, initial_position=Point(-10 * k, 10 * k, 0),
                 role=BodySpec.ROLE_ACTUATED, max_speed=10.0 * k, target=Point(-10 * k, 0, 0),
                 target_weight=1.0, workspace_lower=[-inf, -inf], workspace_upper=[-2.5 * k, inf]),
            body("actuator_2", add=True, radius=1.0 * k, initial_position=Point(5 * k, -5 * k, 0),
                 role=BodySpec.ROLE_ACTUATED, max_speed=10.0 * k, target=Point(10 * k, 0, 0),
                 target_weight=1.0, workspace_lower=[2.5 * k, -inf], workspace_upper=[inf, inf]),
            body("object", add=True, radius=2.0 * k, initial_position=Point(0, 0, 0),
                 target=Point(0, 10 * k, 0), target_weight=1000.0)]
        desk = self.solve(request)
        self.assertEqual(desk.status, SUCCESS, desk.message)
        statistics = desk.solution.statistics
        self.assertAlmostEqual(statistics.length_scale, k, delta=1e-15)
        reference = self.default
        self.assertEqual(statistics.ipopt_iterations, reference.solution.statistics.ipopt_iterations)
        self.assertAlmostEqual(statistics.objective / k ** 2, reference.solution.statistics.objective,
                               delta=1e-9 * reference.solution.statistics.objective)
        contacts = [e.time for e in desk.solution.switches]
        self.assertEqual(len(contacts), len(reference.solution.switches))
        for mine, theirs in zip(contacts, [e.time for e in reference.solution.switches]):
            self.assertAlmostEqual(mine, theirs, delta=1e-9)
        final = {b.name: b.positions[-1] for b in desk.solution.bodies}
        self.assertLess(math.hypot(final["object"].x, final["object"].y - 10 * k), 1e-3 * k)
        self.assertAlmostEqual(desk.solution.verification_error,
                               k * reference.solution.verification_error,
                               delta=1e-6 * k * reference.solution.verification_error)

    def test_custom_scene_given_in_the_message(self):
        request = PlanRequest()
        request.urdf = '<robot name="empty"><link name="world"/></robot>'
        request.bodies = [
            body("pusher", add=True, radius=0.5, initial_position=Point(-3, 0, 0),
                 role=BodySpec.ROLE_ACTUATED, max_speed=4.0),
            body("puck", add=True, radius=0.5, initial_position=Point(0, 0, 0),
                 target=Point(2, 0, 0), target_weight=100.0),
            body("bystander", add=True, radius=0.5, initial_position=Point(0, 4, 0))]
        request.walls = [Wall(name="floor", normal=Vector3(0, 2, 0), offset=-4.0)]  # y >= -2
        request.has_horizon, request.horizon = True, 2.0
        request.has_num_intervals, request.num_intervals = True, 10
        response = self.solve(request)
        self.assertEqual(response.status, SUCCESS, response.message)
        puck = [b for b in response.solution.bodies if b.name == "puck"][0]
        self.assertLess(math.hypot(puck.positions[-1].x - 2.0, puck.positions[-1].y), 0.2)
        touches = [(e.first, e.second) for e in response.solution.switches
                   if e.kind == SwitchEvent.CONTACT]
        self.assertIn(("pusher", "puck"), touches)
        solution = response.solution
        names = {(p.first, p.second) for p in solution.modeled_pairs + solution.checked_pairs +
                 solution.pruned_pairs}
        self.assertIn(("puck", "floor"), names)  # every pair is accounted for

    def test_a_push_along_a_wall_the_pusher_cannot_follow_ends_against_the_wall(self):
        # The pusher is wider than the puck's gap to the wall: no push keeps the puck off it.
        request = PlanRequest()
        request.urdf = '<robot name="empty"><link name="world"/></robot>'
        request.bodies = [
            body("pusher", add=True, radius=0.5, initial_position=Point(-2, 0.3, 0),
                 role=BodySpec.ROLE_ACTUATED, max_speed=4.0),
            body("puck", add=True, radius=0.3, initial_position=Point(0, 0, 0),
                 target=Point(3, 0, 0), target_weight=100.0)]
        request.walls = [Wall(name="floor", normal=Vector3(0, 1, 0), offset=-0.35)]
        request.has_horizon, request.horizon = True, 2.0
        request.has_num_intervals, request.num_intervals = True, 20
        response = self.solve(request)
        self.assertEqual(response.status, Solution.TARGET_NOT_REACHED, response.message)
        self.assertIn("out of the pushers' reach", response.message)
        puck = [b for b in response.solution.bodies if b.name == "puck"][0]
        self.assertAlmostEqual(puck.positions[-1].y, -0.05, delta=1e-6)  # against the wall
        self.assertAlmostEqual(puck.target_distance, 0.05, delta=1e-3)
        self.assertIn("floor", {p.second for p in response.solution.modeled_pairs})

    def test_scene_from_a_urdf_parameter(self):
        response = self.solve(three_disc_request(1.5, 10))
        self.assertEqual(response.status, SUCCESS, response.message)
        self.assertIn("decoration", response.message)  # the link without collision geometry
        self.assertEqual(response.solution.statistics.complementarity_residual, 0.0)

    def test_invalid_requests_are_refused_and_the_node_keeps_serving(self):
        nan = float("nan")
        cases = [
            ([body("ghost")], {}, "unknown link"),
            ([body("object", radius=-1.0)], {}, "radius"),
            ([body("object", override_initial_position=True,
                   initial_position=Point(nan, 0, 0))], {}, "not finite"),
            ([body("actuator_2", override_initial_position=True,
                   initial_position=Point(2.6, 0, 0))], {}, "overlap"),
            ([], {"has_num_elements": True, "num_elements": 0}, "num_elements"),
            ([], {"has_horizon": True, "horizon": 0.0}, "horizon"),
            ([], {"has_horizon": True, "horizon": -1.0}, "horizon"),
            ([], {"has_num_intervals": True, "num_intervals": 100000}, "intervals"),
            ([], {"urdf": "<robot name='broken'><link name="}, "malformed URDF"),
            ([], {"urdf_param": "/no/such/param"}, "no parameter"),
            ([], {"target_accuracy": nan}, "target accuracy must be finite"),
            ([], {"target_accuracy": float("inf")}, "target accuracy must be finite"),
            ([], {"urdf": chain_urdf(20000)}, "too many links: 20000"),
            ([body("object", workspace_lower=[nan, 0.0])], {}, "NaN"),
            ([], {"allowed_pairs": [ContactPair(first="object", second="nobody")]},
             "allowed pair"),
            ([body("actuator_1", role=BodySpec.ROLE_PASSIVE),
              body("actuator_2", role=BodySpec.ROLE_PASSIVE)], {}, "actuated"),
        ]
        for bodies, fields, keyword in cases:
            request = PlanRequest()
            request.bodies = bodies
            for key, value in fields.items():
                setattr(request, key, value)
            self.assert_invalid(request, keyword)  # rosunit reports no subTest failures
        after = self.simulate(SimulateRequest(system="circle_example"))
        self.assertEqual(after.status, SUCCESS, after.message)
        bad = self.simulate(SimulateRequest(system="pendulum"))
        self.assertEqual(bad.status, INVALID_REQUEST)

    def test_impossible_targets_are_infeasible_not_solved(self):
        inf = float("inf")
        cases = [
            ([body("object", workspace_upper=[inf, 5.0])], "outside its workspace"),
            ([body("actuator_1", target=Point(-1000, 0, 0), target_weight=1.0)],
             "cannot reach its target"),
        ]
        for bodies, keyword in cases:
            request = PlanRequest()
            request.bodies = bodies
            response = self.solve(request)
            self.assertEqual(response.status, INFEASIBLE, response.message)
            self.assertEqual(response.solution.status, INFEASIBLE)
            self.assertIn(keyword, response.message)

    def test_a_tiny_wall_time_budget_times_out_with_a_finite_iterate(self):
        # A nanosecond is spent before the first check, on any machine: no race with the clock
        # (a simulation that 1 ms was meant to stop finished within it).
        request = PlanRequest()
        request.has_wall_time_budget, request.wall_time_budget = True, 1e-9
        response = self.solve(request)
        self.assertEqual(response.status, TIMEOUT, response.message)
        self.assertIn("timeout", response.message)
        self.assertLess(response.solution.statistics.wall_time, 10.0)
        self.assertEqual(len(response.solution.states),
                         len(response.solution.times) * response.solution.state_dimension)
        self.assertTrue(all(math.isfinite(v) for v in response.solution.states))
        request = SimulateRequest(system="circle_example")
        request.has_wall_time_budget, request.wall_time_budget = True, 1e-9
        simulated = self.simulate(request)
        self.assertEqual(simulated.status, TIMEOUT, simulated.message)
        self.assertTrue(all(math.isfinite(v) for v in simulated.solution.states))
        request.wall_time_budget = 0.0
        self.assertEqual(self.simulate(request).status, INVALID_REQUEST)

    def test_switches_inside_elements_are_flagged_not_presented_as_resolved(self):
        self.assertTrue(self.default.solution.switches_resolved)
        self.assertEqual(list(self.default.solution.unresolved_elements), [])
        request = small_default(10)
        request.method = PlanRequest.METHOD_STANDARD  # no switch detection
        response = self.solve(request)
        self.assertFalse(response.solution.switches_resolved, response.message)
        self.assertIn("unresolved switch", response.message)
        steps = len(response.solution.step_lengths)
        self.assertTrue(all(e < steps for e in response.solution.unresolved_elements))
        self.assertGreater(len(response.solution.unresolved_elements), 0)

    def test_twenty_repeats_of_one_request_are_bitwise_identical(self):
        request = three_disc_request(1.0, 4)
        request.has_num_elements, request.num_elements = True, 2
        first = self.solve(request)
        self.assertEqual(first.status, SUCCESS, first.message)
        self.assertTrue(first.solution.switches)
        for _ in range(19):
            again = self.solve(request)
            self.assertEqual(again.status, first.status)
            self.assertEqual(again.solution.states, first.solution.states)
            self.assertEqual(again.solution.statistics.objective,
                             first.solution.statistics.objective)
            self.assertEqual(again.solution.statistics.ipopt_iterations,
                             first.solution.statistics.ipopt_iterations)

    def test_random_broken_requests_all_get_a_status_and_a_message(self):
        """Seeded random SolveTrajectory and Simulate requests, most of them broken."""
        rng = random.Random(6)
        statuses = {}
        for _ in range(150):
            response = self.solve(random_request(rng))
            self.assertIn(response.status, ALL_STATUSES_BUT_CANCELLED, response.message)
            statuses[response.status] = statuses.get(response.status, 0) + 1
            if response.status == INVALID_REQUEST:
                self.assertTrue(response.message.startswith("invalid request: "),
                                response.message)
            if response.status != SUCCESS:
                self.assertGreater(len(response.message), 20)
            self.assertTrue(all(math.isfinite(v) for v in response.solution.states))
        self.assertGreater(statuses.get(INVALID_REQUEST, 0), 0)
        # Some requests reach the solver (their budgets of 0.5-1 s may run out on a loaded machine).
        self.assertGreater(len(statuses) - (INVALID_REQUEST in statuses), 0, statuses)
        simulated = {}
        for _ in range(60):
            response = self.simulate(random_simulate_request(rng))
            self.assertIn(response.status, range(Solution.INVALID_REQUEST + 1), response.message)
            simulated[response.status] = simulated.get(response.status, 0) + 1
            if response.status != SUCCESS:
                self.assertGreater(len(response.message), 20)
            self.assertTrue(all(math.isfinite(v) for v in response.solution.states))
        self.assertGreater(simulated.get(SUCCESS, 0), 0, simulated)
        self.assertGreater(simulated.get(INVALID_REQUEST, 0), 0, simulated)
        after = self.simulate(SimulateRequest(system="circle_example"))
        self.assertEqual(after.status, SUCCESS, after.message)

    def test_every_body_has_a_latched_path_at_the_element_boundaries(self):
        response = self.solve(small_default())
        self.assertEqual(response.status, SUCCESS, response.message)
        solution = response.solution
        for body in solution.bodies:
            path = rospy.wait_for_message("/fesd_trajopt/paths/" + body.name, Path, timeout=30.0)
            self.assertEqual(path.header.frame_id, "world")
            self.assertEqual(len(path.poses), len(solution.times))
            stamps = [pose.header.stamp.to_sec() for pose in path.poses]
            self.assertEqual(stamps, sorted(stamps))
            self.assertAlmostEqual(stamps[-1] - stamps[0], solution.times[-1] - solution.times[0],
                                   places=6)
            self.assertAlmostEqual(path.poses[-1].pose.position.x, body.positions[-1].x, places=9)
            self.assertAlmostEqual(path.poses[-1].pose.position.y, body.positions[-1].y, places=9)

    def test_the_frame_of_the_markers_exists_in_tf(self):
        buffer = tf2_ros.Buffer()
        tf2_ros.TransformListener(buffer)
        transform = buffer.lookup_transform("world", "world_fesd_trajopt", rospy.Time(0),
                                            rospy.Duration(10.0))
        self.assertEqual(transform.transform.rotation.w, 1.0)

    def test_markers_arrive_with_the_expected_namespaces(self):
        markers = rospy.wait_for_message("/fesd_trajopt/markers", MarkerArray, timeout=30.0)
        self.assertEqual(markers.markers[0].action, 3)  # DELETEALL first
        namespaces = {m.ns for m in markers.markers[1:]}
        for expected in ["bodies_start", "bodies_final", "targets", "paths",
                         "switch_configurations", "switch_labels"]:
            self.assertIn(expected, namespaces)
        self.assertTrue(all(m.header.frame_id == "world" for m in markers.markers))

    def test_the_push_plan_is_drawn_and_its_guess_residual_reported(self):
        request = PlanRequest()  # the default grid: the residual's scale is the grid's
        request.obstacles = [Obstacle(name="post", radius=0.5, position=Point(x=6.0, y=6.0))]
        response = self.solve(request)
        self.assertEqual(response.status, Solution.SUCCESS, response.message)
        residual = response.solution.statistics.guess_residual
        self.assertTrue(0.0 < residual < 1.0, residual)  # the default scene's plan: about 0.4
        markers = rospy.wait_for_message("/fesd_trajopt/markers", MarkerArray, timeout=30.0)
        legs = [m for m in markers.markers if m.ns == "plan_legs"]
        self.assertEqual(len(legs), 1)  # the object's push: from its start to its target
        self.assertAlmostEqual(legs[0].points[0].y, 0.0, places=9)
        self.assertAlmostEqual(legs[0].points[1].y, 10.0, places=9)
        transits = [m for m in markers.markers if m.ns == "plan_transits"]
        self.assertEqual(len(transits), 4)  # each actuator's approach and return
        for transit in transits:
            self.assertGreater(len(transit.points), 0)
            self.assertEqual(len(transit.points) % 2, 0)  # dashes: pairs of points

    def test_concurrent_calls_are_both_answered_correctly(self):
        requests = [small_default(10), small_default(12)]
        sequential = [self.solve(r) for r in requests]
        results = [None, None]

        def call(i):
            results[i] = rospy.ServiceProxy(SOLVE, SolveTrajectory)(requests[i])

        threads = [threading.Thread(target=call, args=(i,)) for i in range(2)]
        for t in threads:
            t.start()
        for t in threads:
            t.join(timeout=300.0)
        for alone, together in zip(sequential, results):
            self.assertEqual(together.status, SUCCESS, together.message)
            self.assertEqual(together.solution.states, alone.solution.states)

    def test_the_same_request_gives_the_same_answer(self):
        first, second = self.solve(small_default(10)), self.solve(small_default(10))
        self.assertEqual(first.status, SUCCESS, first.message)
        self.assertEqual(first.solution.states, second.solution.states)
        self.assertEqual(first.solution.statistics.ipopt_iterations,
                         second.solution.statistics.ipopt_iterations)

    def test_a_far_away_body_is_pruned(self):
        request = PlanRequest()
        request.bodies = [body("far", add=True, radius=1.0, initial_position=Point(1e4, 1e4, 0))]
        response = self.solve(request)
        self.assertEqual(response.status, SUCCESS, response.message)
        pruned = {(p.first, p.second) for p in response.solution.pruned_pairs}
        for other in ["actuator_1", "actuator_2", "object"]:
            self.assertIn((other, "far"), pruned)
        self.assertEqual(len(response.solution.modeled_pairs), 2)
        # A passive body nothing can reach never moves: it adds no variable and no constraint.
        for field in ["nlp_variables", "nlp_constraints", "complementarity_constraints"]:
            self.assertEqual(getattr(response.solution.statistics, field),
                             getattr(self.default.solution.statistics, field), field)
        far = [b for b in response.solution.bodies if b.name == "far"][0]
        self.assertTrue(all(p.x == 1e4 and p.y == 1e4 for p in far.positions))
        moving = {b.name: b.positions for b in response.solution.bodies}
        for b in self.default.solution.bodies:  # the same NLP, so the very same plan
            self.assertEqual(moving[b.name], b.positions, b.name)

    def test_bodies_in_reach_off_the_path_are_checked_on_the_answer_not_modelled(self):
        rocks = [body("rock_%d" % i, add=True, radius=1.0, initial_position=Point(x, -12, 0))
                 for i, x in enumerate([-4.0, 0.0, 4.0])]
        lazy = small_default(10)
        lazy.bodies = rocks
        response = self.solve(lazy)
        self.assertEqual(response.status, SUCCESS, response.message)
        solution = response.solution
        self.assertEqual({(p.first, p.second) for p in solution.modeled_pairs},
                         {("actuator_1", "object"), ("actuator_2", "object")})
        self.assertEqual(solution.statistics.pair_rounds, 1)
        checked = {(p.first, p.second): p for p in solution.checked_pairs}
        self.assertIn(("actuator_2", "rock_1"), checked)
        for pair in solution.checked_pairs:  # each stays beyond the margin, 0.1 of its radii
            self.assertGreater(pair.min_distance, 0.1 * 3.0, pair)
            self.assertIn("checked on the solution", pair.reason)
        for pair in solution.modeled_pairs:  # no penetration where the plan holds them apart
            self.assertGreater(pair.min_distance, -1e-9, pair)
        for pair in solution.pruned_pairs:
            self.assertTrue(math.isnan(pair.min_distance), pair)
        small = self.solve(small_default(10))
        final = {b.name: b.positions[-1] for b in solution.bodies}
        for b in small.solution.bodies:  # the same NLP as without the rocks: the same plan
            self.assertEqual(final[b.name], b.positions[-1], b.name)

        every = small_default(10)
        every.bodies = rocks
        every.contact_pairs = PlanRequest.PAIRS_ALL_IN_REACH
        response = self.solve(every)
        self.assertEqual(response.status, SUCCESS, response.message)
        self.assertEqual(len(response.solution.checked_pairs), 0)
        self.assertEqual(len(response.solution.modeled_pairs),
                         len(solution.modeled_pairs) + len(solution.checked_pairs))
        self.assertGreater(response.solution.statistics.nlp_variables,
                           solution.statistics.nlp_variables)
        for b in response.solution.bodies:  # every pair in reach modelled: the same plan
            end = b.positions[-1]
            self.assertLess(math.hypot(end.x - final[b.name].x, end.y - final[b.name].y), 1e-6)

    def test_a_scene_where_nothing_can_touch_is_one_smooth_nlp(self):
        request = PlanRequest()
        request.urdf = '<robot name="empty"><link name="world"/></robot>'
        request.bodies = [
            body("mover", add=True, radius=0.5, role=BodySpec.ROLE_ACTUATED, max_speed=1.0,
                 target=Point(1, 0, 0), target_weight=10.0),
            body("rock", add=True, radius=0.5, initial_position=Point(0, 10, 0))]
        request.has_horizon, request.horizon = True, 2.0
        request.has_num_intervals, request.num_intervals = True, 10
        response = self.solve(request)
        self.assertEqual(response.status, SUCCESS, response.message)
        statistics = response.solution.statistics
        self.assertEqual(statistics.complementarity_constraints, 0)
        self.assertEqual(statistics.homotopy_steps, 1)
        self.assertEqual(len(response.solution.modeled_pairs), 0)
        mover = [b for b in response.solution.bodies if b.name == "mover"][0]
        # min 1e-4 T u^2 + 10 (T u - 1)^2 with T = 2 (control weight from config/): the optimal
        # constant u gives p(T) = 2 u = 1 / (1 + 5e-6).
        self.assertAlmostEqual(mover.positions[-1].x, 1.0 / (1.0 + 5e-6), delta=1e-7)
        self.assertAlmostEqual(mover.positions[-1].y, 0.0, delta=1e-7)

    def test_simulate_circle_example_matches_the_analytic_solution(self):
        request = SimulateRequest(system="circle_example")
        request.has_num_steps, request.num_steps = True, 10
        request.has_num_elements, request.num_elements = True, 2
        request.has_num_stages, request.num_stages = True, 4
        response = self.simulate(request)
        self.assertEqual(response.status, SUCCESS, response.message)
        states = response.solution.states
        self.assertEqual(response.solution.state_dimension, 2)
        self.assertLess(math.hypot(states[-2] + 1.0, states[-1]), 1e-8)
        times = sorted(e.time for e in response.solution.switches)
        self.assertEqual(len(times), 2)
        self.assertAlmostEqual(times[0], 5 * math.pi / 12, delta=1e-6)
        self.assertAlmostEqual(times[1], 5 * math.pi / 12 + math.sqrt(3), delta=1e-6)

    def test_simulate_a_scene_under_commands(self):
        request = SimulateRequest()
        request.urdf_param = "/three_disc_scene"
        request.bodies = [body("pusher", role=BodySpec.ROLE_ACTUATED)]
        request.commands = [BodyTrajectory(name="pusher", controls=[Vector3(2.0, 0, 0)])]
        request.has_horizon, request.horizon = True, 2.0
        request.has_num_steps, request.num_steps = True, 4
        response = self.simulate(request)
        self.assertEqual(response.status, SUCCESS, response.message)
        final = {b.name: b.positions[-1] for b in response.solution.bodies}
        # The pusher reaches the puck at x = -1 after 1 s. In contact, the projection onto the
        # tangent cone shares the commanded velocity between the two discs: both move at 1 m/s.
        self.assertAlmostEqual(final["pusher"].x, 0.0, delta=1e-6)
        self.assertAlmostEqual(final["puck"].x, 1.0, delta=1e-6)
        contact = [e for e in response.solution.switches if e.kind == SwitchEvent.CONTACT]
        self.assertAlmostEqual(contact[0].time, 1.0, delta=1e-6)

    def turning_bar_request(self):
        """A pusher at (-1, 0.3) driven along x into the upper sphere of a bar of two spheres
        (radius 0.25 at y = +-0.3) that turns: it turns clockwise (test_turning_bodies)."""
        request = SimulateRequest()
        request.urdf = '<robot name="empty"><link name="world"/></robot>'
        request.bodies = [
            body("pusher", add=True, radius=0.2, initial_position=Point(-1, 0.3, 0),
                 role=BodySpec.ROLE_ACTUATED),
            body("bar", add=True, turns=True, initial_position=Point(0, 0, 0),
                 sphere_offsets=[Point(0, -0.3, 0), Point(0, 0.3, 0)], sphere_radii=[0.25, 0.25])]
        request.commands = [BodyTrajectory(name="pusher", controls=[Vector3(1.0, 0, 0)])]
        request.has_horizon, request.horizon = True, 1.5
        request.has_num_steps, request.num_steps = True, 15
        return request

    def test_simulate_turns_a_bar_of_spheres_pushed_off_centre(self):
        response = self.simulate(self.turning_bar_request())
        self.assertEqual(response.status, SUCCESS, response.message)
        bar = [b for b in response.solution.bodies if b.name == "bar"][0]
        self.assertEqual(len(bar.yaws), len(response.solution.times))
        self.assertEqual(len(bar.sphere_offsets), 2)
        self.assertGreater(bar.turning_radius, 0.0)
        self.assertTrue(math.isnan(bar.target_yaw_distance))
        # The end of an RK4 integration of the written-out projection (test_turning_bodies):
        # s = rho yaw = -0.2929045355 at t = 1.5, the bar's centre at (0.3330495, -0.0464659).
        self.assertAlmostEqual(bar.yaws[-1] * bar.turning_radius, -0.2929045355, delta=1e-5)
        self.assertAlmostEqual(bar.positions[-1].x, 0.3330495, delta=1e-5)
        self.assertAlmostEqual(bar.positions[-1].y, -0.0464659, delta=1e-5)
        contact = [e for e in response.solution.switches if e.kind == SwitchEvent.CONTACT]
        self.assertAlmostEqual(contact[0].time, 0.55, delta=1e-8)

    def test_a_urdf_link_of_spheres_on_a_planar_joint_turns_and_is_answered_as_its_joint(self):
        # turning_bar_request's bar moved 1 along x, as a link on a planar joint whose frame is
        # turned a quarter turn: the same motion, and joint coordinates in that frame.
        request = self.turning_bar_request()
        request.urdf = """<robot name="r"><link name="world"/><link name="bar">
            <collision><origin xyz="-0.3 0 0"/><geometry><sphere radius="0.25"/></geometry></collision>
            <collision><origin xyz="0.3 0 0"/><geometry><sphere radius="0.25"/></geometry></collision>
          </link><joint name="bar_joint" type="planar"><parent link="world"/><child link="bar"/>
            <origin xyz="1 0 0" rpy="0 0 1.5707963267948966"/><axis xyz="0 0 1"/></joint></robot>"""
        request.bodies = [body("pusher", add=True, radius=0.2, initial_position=Point(0, 0.3, 0),
                               role=BodySpec.ROLE_ACTUATED)]
        response = self.simulate(request)
        self.assertEqual(response.status, SUCCESS, response.message)
        bar = [b for b in response.solution.bodies if b.name == "bar"][0]
        self.assertAlmostEqual(bar.yaws[-1] * bar.turning_radius, -0.2929045355, delta=1e-5)
        self.assertAlmostEqual(bar.positions[-1].x, 1.3330495, delta=1e-5)
        self.assertAlmostEqual(bar.positions[-1].y, -0.0464659, delta=1e-5)
        motion = response.solution.joint_trajectory
        self.assertEqual(motion.joint_names, ["bar_joint/x", "bar_joint/y", "bar_joint/theta"])
        self.assertEqual(len(motion.points), len(response.solution.times))
        for start in motion.points[0].positions:
            self.assertAlmostEqual(start, 0.0, delta=1e-12)
        x, y, theta = motion.points[-1].positions
        self.assertAlmostEqual(x, -0.0464659, delta=1e-5)
        self.assertAlmostEqual(y, -0.3330495, delta=1e-5)
        self.assertAlmostEqual(theta, bar.yaws[-1], delta=1e-12)

        request.bodies.append(body("bar", override_initial_position=True,
                                   initial_position=Point(1, 0.5, 0), initial_yaw=0.1))
        response = self.simulate(request)
        self.assertEqual(response.status, SUCCESS, response.message)
        bar = [b for b in response.solution.bodies if b.name == "bar"][0]
        self.assertAlmostEqual(bar.yaws[0], 0.1, delta=1e-15)
        self.assertAlmostEqual(bar.positions[0].y, 0.5, delta=1e-15)
        x, y, theta = response.solution.joint_trajectory.points[0].positions
        self.assertAlmostEqual(x, 0.5, delta=1e-12)  # the joint's x is the world's y
        self.assertAlmostEqual(theta, 0.1, delta=1e-15)
        for spec, words in ((body("bar", radius=0.3), "collision spheres in the URDF"),
                            (body("bar", initial_yaw=0.3), "override_initial_position")):
            request.bodies[-1] = spec
            response = self.simulate(request)
            self.assertEqual(response.status, INVALID_REQUEST, response.message)
            self.assertIn(words, response.message)

    def test_hostile_turning_bodies_are_refused_and_the_node_keeps_serving(self):
        def bar(**fields):
            request = small_default()
            spec = body("bar", add=True, turns=True, initial_position=Point(0, 5, 0),
                        sphere_offsets=[Point(0, -0.3, 0), Point(0, 0.3, 0)],
                        sphere_radii=[0.25, 0.25])
            for key, value in fields.items():
                setattr(spec, key, value)
            request.bodies = [spec]
            return request
        self.assert_invalid(bar(sphere_radii=[0.25]), "radii")
        self.assert_invalid(bar(initial_yaw=float("nan")), "not finite")
        self.assert_invalid(bar(target_yaw=float("inf"), target_yaw_weight=1.0), "not finite")
        self.assert_invalid(bar(sphere_radii=[0.25, 0.0]), "radius")
        self.assert_invalid(bar(sphere_offsets=[Point(0, i, 0) for i in range(5000)],
                                sphere_radii=[0.1] * 5000), "limit")
        self.assert_invalid(bar(role=BodySpec.ROLE_ACTUATED), "only passive bodies turn")
        self.assert_invalid(bar(turns=False, initial_yaw=0.5), "does not turn")
        self.assert_invalid(bar(add=False, name="object"), "spheres come from")
        self.assert_invalid(bar(sphere_offsets=[Point(0, 0, 0)], sphere_radii=[0.25]), "one sphere")
        self.assert_invalid(bar(sphere_offsets=[Point(0, -0.3, 0.1), Point(0, 0.3, 0)]),
                            "off the plane")
        self.assert_invalid(bar(turning_radius=1e-9), "turning radius")
        self.assertEqual(self.solve(small_default()).status, SUCCESS)

    def test_a_turning_bodys_position_is_its_spheres_centre_of_pressure(self):
        # Spheres at y = 0 and 0.6 (radii 0.1, 0.2: areas 1 : 4) given about any origin: the body
        # stays at initial_position and its offsets move by their centre of pressure, y = 0.48.
        request = self.turning_bar_request()
        request.bodies[1] = body("bar", add=True, turns=True, initial_position=Point(0, 3, 0),
                                 initial_yaw=0.2, sphere_offsets=[Point(0, 0, 0), Point(0, 0.6, 0)],
                                 sphere_radii=[0.1, 0.2])
        response = self.simulate(request)
        self.assertEqual(response.status, SUCCESS, response.message)
        bar = [b for b in response.solution.bodies if b.name == "bar"][0]
        self.assertAlmostEqual(bar.positions[0].x, 0.0, delta=1e-12)
        self.assertAlmostEqual(bar.positions[0].y, 3.0, delta=1e-12)
        self.assertAlmostEqual(bar.yaws[0], 0.2, delta=1e-12)
        self.assertAlmostEqual(bar.sphere_offsets[0].y, -0.48, delta=1e-12)
        self.assertAlmostEqual(bar.sphere_offsets[1].y, 0.12, delta=1e-12)

    def block(self, array, *index):
        """One entry of a row-major Float64MultiArray."""
        offset = sum(i * d.stride // (d.size or 1) for i, d in zip(index, array.layout.dim))
        return array.data[offset]

    def simulate_with_sensitivities(self, request):
        """A successful simulation whose sensitivities are all defined."""
        request.sensitivities = True
        response = self.simulate(request)
        self.assertEqual(response.status, SUCCESS, response.message)
        self.assertTrue(response.sensitivities.all_defined,
                        response.sensitivities.undefined_reason)
        return response

    def test_simulate_returns_the_exact_sensitivity_across_a_crossing(self):
        # x' = 2 - sign(x) from -1: x(T) = T + x0 / 3 after the crossing at -x0 / 3.
        request = SimulateRequest(system="two_minus_sign")
        request.has_num_steps, request.num_steps = True, 10
        response = self.simulate_with_sensitivities(request)
        sensitivities = response.sensitivities
        self.assertEqual(sensitivities.state_names, ["x"])
        by_start = sensitivities.state_by_initial_state
        self.assertEqual([(d.label, d.size) for d in by_start.layout.dim],
                         [("step", 10), ("state", 1), ("initial_state", 1)])
        self.assertAlmostEqual(self.block(by_start, 9, 0, 0), 1.0 / 3.0, delta=1e-8)
        self.assertAlmostEqual(self.block(by_start, 0, 0, 0), 1.0, delta=1e-10)  # before it
        self.assertEqual(len(sensitivities.switch_time_by_initial_state.data),
                         len(response.solution.switches))
        for derivative in sensitivities.switch_time_by_initial_state.data:
            self.assertAlmostEqual(derivative, -1.0 / 3.0, delta=1e-8)
        request.initial_state = [-0.5]
        moved = self.simulate(request)
        self.assertAlmostEqual(moved.solution.states[-1], 2.0 - 0.5 / 3.0, delta=1e-9)

    def test_simulate_returns_the_exact_sensitivities_into_a_sliding_mode(self):
        # x1 reaches 0 at t* = 2 x1(0) and slides; x2(T) = x2(0) + x1(0) + T / 2.
        request = SimulateRequest(system="sliding")
        request.has_num_steps, request.num_steps = True, 8
        response = self.simulate_with_sensitivities(request)
        sensitivities = response.sensitivities
        by_start = sensitivities.state_by_initial_state
        for row, column, value in [(0, 0, 0.0), (0, 1, 0.0), (1, 0, 1.0), (1, 1, 1.0)]:
            self.assertAlmostEqual(self.block(by_start, 7, row, column), value, delta=1e-8)
        self.assertAlmostEqual(response.solution.states[-1], 0.2 + 0.37 + 1.0, delta=1e-9)
        entering = sensitivities.switch_time_by_initial_state
        self.assertAlmostEqual(self.block(entering, 0, 0), 2.0, delta=1e-8)  # t* = 2 x1(0)

    def test_simulate_a_push_returns_the_saltation_of_the_projection(self):
        # The pusher (at -3, 2 m/s) meets the puck at t = 1 inside the third step of 0.4 s; from
        # then on both move at 1 m/s: the puck gains half of every shift of either start and
        # half of every extra metre the pusher is commanded.
        request = SimulateRequest()
        request.urdf_param = "/three_disc_scene"
        request.bodies = [body("pusher", role=BodySpec.ROLE_ACTUATED),
                          body("far", add=True, radius=0.5, initial_position=Point(0, -8, 0))]
        request.commands = [BodyTrajectory(name="pusher", controls=[Vector3(2.0, 0, 0)])]
        request.has_horizon, request.horizon = True, 2.0
        request.has_num_steps, request.num_steps = True, 5
        sensitivities = self.simulate_with_sensitivities(request).sensitivities
        names, controls = sensitivities.state_names, sensitivities.control_names
        puck_x, pusher_x = names.index("puck/x"), names.index("pusher/x")
        by_start, by_controls = sensitivities.state_by_initial_state, sensitivities.state_by_controls
        self.assertAlmostEqual(self.block(by_start, 4, puck_x, pusher_x), 0.5, delta=1e-8)
        self.assertAlmostEqual(self.block(by_start, 4, puck_x, puck_x), 0.5, delta=1e-8)
        far_y = names.index("far/y")  # out of reach: it stays where it starts
        self.assertEqual(self.block(by_start, 4, far_y, far_y), 1.0)
        self.assertEqual(self.block(by_start, 4, puck_x, far_y), 0.0)
        push = controls.index("pusher/vx")
        for step in range(5):
            self.assertAlmostEqual(self.block(by_controls, 4, puck_x, step * len(controls) + push),
                                   0.2, delta=1e-8)
            self.assertEqual(self.block(by_controls, 0, puck_x, step * len(controls) + push), 0.0)

    def test_the_closed_loop_example_ends_a_push_at_its_target_that_open_loop_misses(self):
        script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts",
                              "closed_loop_demo.py")
        run = subprocess.run(["/usr/bin/python3", script, "--every", "4"],
                             capture_output=True, text=True, timeout=300)
        self.assertEqual(run.returncode, 0, run.stdout + run.stderr)
        self.assertIn("needs feedback", run.stdout)
        last = run.stdout.strip().splitlines()[-1]
        closed = float(last.split(" ends ")[1].split(" from")[0])
        open_loop = float(last.split("feedback, ")[1].split(" without")[0])
        self.assertLess(closed, 1e-2, run.stdout)
        self.assertGreater(open_loop, 0.1, run.stdout)
        self.assertEqual(run.stdout.count(" warm "), 9, run.stdout)  # after 4, 8, .., 36 of 40

    def test_the_gradient_step_example_lowers_its_cost(self):
        script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts",
                              "gradient_step_demo.py")
        run = subprocess.run(["/usr/bin/python3", script, "--iterations", "4"],
                             capture_output=True, text=True, timeout=120)
        self.assertEqual(run.returncode, 0, run.stdout + run.stderr)
        costs = [float(line.split("cost ")[1].split(",")[0]) for line in run.stdout.splitlines()]
        self.assertEqual(len(costs), 4, run.stdout)
        self.assertLess(costs[-1], 0.5 * costs[0], run.stdout)

    def test_sensitivities_beyond_the_limits_are_refused_and_the_node_keeps_serving(self):
        crowded = SimulateRequest(sensitivities=True)
        crowded.urdf = '<robot name="empty"><link name="world"/></robot>'
        crowded.bodies = [body("pusher", add=True, radius=0.1, initial_position=Point(0, 0, 0),
                               role=BodySpec.ROLE_ACTUATED)]
        crowded.bodies += [body("b%d" % i, add=True, radius=0.1, initial_position=Point(i, 5, 0))
                           for i in range(29)]
        crowded.has_num_steps, crowded.num_steps = True, 200
        refused = self.simulate(crowded)
        self.assertEqual(refused.status, INVALID_REQUEST, refused.message)
        self.assertIn("max_sensitivity_entries", refused.message)
        for system, start, keyword in [("spiral", [1.0], "initial_state"),
                                       ("two_minus_sign", [float("nan")], "finite"),
                                       ("", [0.0], "built-in systems")]:
            request = SimulateRequest(system=system, initial_state=start, sensitivities=True)
            request.urdf_param = "/three_disc_scene"
            response = self.simulate(request)
            self.assertEqual(response.status, INVALID_REQUEST, response.message)
            self.assertIn(keyword, response.message)
        self.simulate_with_sensitivities(SimulateRequest(system="spiral"))


if __name__ == "__main__":
    rostest.rosrun("fesd_trajopt", "node_services", NodeServices)
