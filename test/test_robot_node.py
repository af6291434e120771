#!/usr/bin/python3
"""Integration tests of the fesd_trajopt node on a robot scene: the shipped planar arm
(config/robots/planar_arm.urdf, joints shoulder, elbow, wrist about z) pushing a disc, joint
settings refused by name, a joint velocity command simulated, ~joint_states during playback, a
robot goal of the ~plan action with feedback and cancel, a replan's warm start, pucks given in
the robot's URDF (one sphere or several), and the spherized Panda pushing a puck on a table."""
import math
import time
import unittest

import actionlib
import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from fesd_trajopt.msg import (BodySpec, BodyTrajectory, ContactPair, JointSpec, PlanRequest,
                              PlanTrajectoryAction, PlanTrajectoryGoal, Solution, Wall)
from fesd_trajopt.srv import Simulate, SimulateRequest, SolveTrajectory
from geometry_msgs.msg import Point, Vector3
from sensor_msgs.msg import JointState
from trajectory_msgs.msg import JointTrajectoryPoint
from visualization_msgs.msg import MarkerArray

SOLVE = "/fesd_trajopt/solve_trajectory"
SIMULATE = "/fesd_trajopt/simulate"
PLAN = "/fesd_trajopt/plan"
ARM = "/planar_arm"
PANDA = "/panda"
JOINTS = ["shoulder", "elbow", "wrist"]
SPEED_LIMITS = [1.0, 1.5, 2.0]  # the URDF's <limit velocity>
INTERVALS, ELEMENTS = 10, 2


def panda_on_the_table(body):
    """The spherized Panda at its ready pose with `body` on the table z >= 0."""
    request = PlanRequest()
    request.urdf_param = PANDA
    request.bodies = [body]
    request.walls = [Wall(name="table", normal=Vector3(0.0, 0.0, 1.0), offset=0.0)]
    ready = [0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785]
    request.joints = [JointSpec(name="panda_joint%d" % (j + 1), has_initial_position=True,
                                initial_position=q) for j, q in enumerate(ready)]
    return request


def arm_push_request():
    """The shipped push (examples/robot_scenes.h): the arm from (-0.6, 0, 0) pushes a disc of
    radius 0.05 from (0.6, 0) to (0.6, 0.2) in 2 s."""
    request = PlanRequest()
    request.urdf_param = ARM
    request.bodies = [BodySpec(name="disc", add=True, radius=0.05,
                               initial_position=Point(0.6, 0.0, 0.0), role=BodySpec.ROLE_PASSIVE,
                               target=Point(0.6, 0.2, 0.0), target_weight=100.0)]
    request.joints = [JointSpec(name="shoulder", has_initial_position=True, initial_position=-0.6)]
    request.has_horizon, request.horizon = True, 2.0
    request.has_num_intervals, request.num_intervals = True, INTERVALS
    request.has_num_elements, request.num_elements = True, ELEMENTS
    request.contact_pairs = PlanRequest.PAIRS_ALL_IN_REACH
    request.verify = True
    return request


class RobotNodeTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_robot_node", anonymous=True)
        rospy.wait_for_service(SOLVE, timeout=60.0)
        cls.solve = rospy.ServiceProxy(SOLVE, SolveTrajectory)
        cls.simulate = rospy.ServiceProxy(SIMULATE, Simulate)

    def assert_invalid(self, request, *keywords):
        response = self.solve(request)
        self.assertEqual(response.status, Solution.INVALID_REQUEST, response.message)
        for keyword in keywords:
            self.assertIn(keyword, response.message)

    def test_arm_pushes_the_disc_to_its_target(self):
        markers = []
        sub = rospy.Subscriber("/fesd_trajopt/markers", MarkerArray, markers.append)
        states = []
        joint_sub = rospy.Subscriber("/fesd_trajopt/joint_states", JointState, states.append)
        start = time.time()
        response = self.solve(arm_push_request())
        seconds = time.time() - start
        solution = response.solution
        print("planar arm push through the node: status %d in %.2f s (%s), verification error "
              "%.2e, switches %s" % (response.status, seconds, response.message,
                                     solution.verification_error,
                                     [(round(s.time, 4), s.first, s.second) for s in
                                      solution.switches]))
        self.assertEqual(response.status, Solution.SUCCESS, response.message)
        disc = solution.bodies[0]
        self.assertEqual(disc.name, "disc")
        self.assertLess(math.hypot(disc.positions[-1].x - 0.6, disc.positions[-1].y - 0.2), 1e-3)
        self.assertLess(disc.target_distance, 1e-3)
        self.assertLess(solution.verification_error, 1e-3)
        self.assertEqual([(r.num_stages, r.num_elements) for r in solution.refinements],
                         [(2, ELEMENTS)])  # the node's ~target_accuracy 1e-2, met at once
        # A point per element boundary, at the solution's times, from the requested start.
        motion = solution.joint_trajectory
        self.assertEqual(list(motion.joint_names), JOINTS)
        self.assertEqual(len(solution.times), INTERVALS * ELEMENTS + 1)
        self.assertEqual(len(motion.points), len(solution.times))
        for point, t in zip(motion.points, solution.times):
            self.assertAlmostEqual(point.time_from_start.to_sec(), t, places=6)
            self.assertEqual(len(point.positions), 3)
            self.assertEqual(len(point.velocities), 3)
        self.assertAlmostEqual(motion.points[0].positions[0], -0.6, places=12)
        # The commands: one per control interval, within the URDF's speed limits.
        commands = solution.joint_commands
        self.assertEqual(list(commands.joint_names), JOINTS)
        self.assertEqual(len(commands.points), INTERVALS)
        for point in commands.points:
            for u, limit in zip(point.velocities, SPEED_LIMITS):
                self.assertLessEqual(abs(u), limit + 1e-6)
        # Contacts name a sphere of the arm and the disc.
        contacts = [s for s in solution.switches if s.kind == s.CONTACT]
        self.assertTrue(contacts)
        for event in contacts:
            link, sphere = event.first.split("/")
            self.assertIn(link, ["upper_arm", "forearm", "hand"])
            self.assertTrue(sphere.startswith("sphere_"), event.first)
            self.assertEqual(event.second, "disc")
        # The markers show the arm's spheres at the start, the end and every switch.
        deadline = time.time() + 5.0
        while not markers and time.time() < deadline:
            rospy.sleep(0.1)
        namespaces = {}
        for marker in markers[-1].markers:
            namespaces[marker.ns] = namespaces.get(marker.ns, 0) + 1
        spheres = 1 + 3 + 3 + 2
        self.assertEqual(namespaces.get("robot_start"), spheres)
        self.assertEqual(namespaces.get("robot_final"), spheres)
        self.assertEqual(namespaces.get("robot_switch_configurations"),
                         spheres * len(solution.switches))
        # The playback publishes the joints, moving along the plan.
        deadline = time.time() + 5.0
        while len(states) < 10 and time.time() < deadline:
            rospy.sleep(0.1)
        sub.unregister()
        joint_sub.unregister()
        self.assertGreaterEqual(len(states), 10)
        self.assertEqual(list(states[-1].name), JOINTS)
        shoulders = [s.position[0] for s in states]
        low = min(p.positions[0] for p in motion.points)
        high = max(p.positions[0] for p in motion.points)
        for q in shoulders:
            self.assertTrue(low - 1e-9 <= q <= high + 1e-9, (q, low, high))
        self.assertGreater(max(shoulders) - min(shoulders), 1e-3)  # it moves

    def test_the_arm_turns_a_bar_to_a_pose(self):
        request = arm_push_request()
        request.bodies[0] = BodySpec(
            name="bar", add=True, turns=True, initial_position=Point(0.6, 0.0, 0.0),
            sphere_offsets=[Point(-0.05, 0.0, 0.0), Point(0.05, 0.0, 0.0)],
            sphere_radii=[0.04, 0.04], role=BodySpec.ROLE_PASSIVE, target=Point(0.6, 0.2, 0.0),
            target_weight=100.0, target_yaw=0.3, target_yaw_weight=100.0)
        start = time.time()
        response = self.solve(request)
        print("planar arm turns a bar through the node: status %d in %.2f s (%s)"
              % (response.status, time.time() - start, response.message))
        self.assertEqual(response.status, Solution.SUCCESS, response.message)
        bar = response.solution.bodies[0]
        self.assertLess(bar.target_distance, 1e-3)
        self.assertLess(bar.target_yaw_distance, 1e-3)
        self.assertEqual(len(bar.yaws), len(bar.positions))
        self.assertAlmostEqual(bar.yaws[0], 0.0, places=12)
        self.assertAlmostEqual(bar.yaws[-1], 0.3, delta=1e-3)
        self.assertLess(response.solution.verification_error, 1e-3)

    def test_an_accuracy_target_refines_the_arms_plan(self):
        request = arm_push_request()
        request.target_accuracy = 1e-6
        response = self.solve(request)
        rungs = response.solution.refinements
        print("planar arm push to 1e-6: status %d, rungs %s" % (
            response.status, [(r.num_stages, r.num_elements, r.verification_error, r.wall_time)
                              for r in rungs]))
        self.assertIn(response.status, [Solution.SUCCESS, Solution.ACCURACY_NOT_MET],
                      response.message)
        self.assertGreaterEqual(len(rungs), 2)
        self.assertEqual((rungs[0].num_stages, rungs[0].num_elements), (2, ELEMENTS))
        for before, rung in zip(rungs, rungs[1:]):
            self.assertEqual(rung.error_before, before.verification_error)
            self.assertTrue(rung.change, rung)
        best = min(r.verification_error for r in rungs)
        self.assertEqual(response.solution.verification_error, best)
        self.assertEqual(response.status == Solution.SUCCESS, best <= 1e-6)
        self.assertIn("accuracy target 1e-06", response.message)

    def test_pucks_in_the_robots_urdf_are_free_bodies_of_its_scene(self):
        # The arm push with the disc given in the URDF, on a floating joint of the base: the
        # request names it to give its target, as a body of a disc scene's URDF.
        urdf = rospy.get_param(ARM).replace("</robot>", """
          <link name="puck"><collision><geometry><sphere radius="0.05"/></geometry></collision>
          </link>
          <joint name="puck_joint" type="floating"><parent link="base"/><child link="puck"/>
            <origin xyz="0.6 0 0"/></joint></robot>""")
        request = arm_push_request()
        request.urdf_param, request.urdf = "", urdf
        request.bodies = [BodySpec(name="puck", target=Point(0.6, 0.2, 0.0), target_weight=100.0)]
        response = self.solve(request)
        self.assertEqual(response.status, Solution.SUCCESS, response.message)
        puck = response.solution.bodies[0]
        self.assertEqual(puck.name, "puck")
        self.assertAlmostEqual(puck.positions[0].x, 0.6, places=12)
        self.assertLess(puck.target_distance, 1e-3)
        self.assertLess(response.solution.verification_error, 1e-3)
        # Two spheres side by side: one body at their mean, pushed sphere by sphere.
        two_spheres = urdf.replace("</collision>\n          </link>", """</collision>
          <collision><origin xyz="0.1 0 0"/><geometry><sphere radius="0.05"/></geometry>
          </collision></link>""")
        request.urdf = two_spheres
        request.bodies[0].target = Point(0.65, 0.2, 0.0)
        request.contact_pairs = PlanRequest.PAIRS_DEFAULT  # few pairs in reach: all modelled
        response = self.solve(request)
        print("two-sphere puck in the URDF: status %d, %d Ipopt iterations, %.2e from its target"
              % (response.status, response.solution.statistics.ipopt_iterations,
                 response.solution.bodies[0].target_distance))
        self.assertEqual(response.status, Solution.SUCCESS, response.message)
        self.assertEqual(len(response.solution.checked_pairs), 0)
        self.assertGreaterEqual(len(response.solution.modeled_pairs), 18)  # 9 arm x 2 puck spheres
        puck = response.solution.bodies[0]
        self.assertAlmostEqual(puck.positions[0].x, 0.65, places=12)
        self.assertLess(puck.target_distance, 1e-3)
        self.assertTrue(any(e.first.startswith("puck/sphere_") or
                            e.second.startswith("puck/sphere_")
                            for e in response.solution.switches), response.solution.switches)
        # Its size comes from its spheres; a free link without one is refused by name.
        request.bodies[0].radius = 0.1
        self.assert_invalid(request, "body 'puck' carries 2 collision spheres in the URDF")
        request.bodies[0].radius = 0.0
        request.urdf = urdf.replace('<link name="puck"><collision><geometry><sphere radius="0.05"/>',
                                    '<link name="puck"><collision><geometry><box size="1 1 1"/>')
        self.assert_invalid(request, "free link 'puck' (joint 'puck_joint') has no collision "
                                     "sphere")

    def test_the_panda_pushes_a_puck_across_the_table(self):
        # The shipped spatial push (examples/robot_scenes.h, pandaPushTask): the spherized Panda
        # from its ready pose pushes a puck 0.2 m along x on a table (z >= 0), lazy pairs,
        # inferred spatial; one rung (no accuracy ladder), unverified, as bench robot-push. Its
        # 118 pairs in reach are more than ~robot_all_pairs_up_to: lazy by default.
        request = panda_on_the_table(BodySpec(name="puck", add=True, radius=0.05,
                                              initial_position=Point(0.45, 0.0, 0.05),
                                              target=Point(0.65, 0.0, 0.05), target_weight=100.0))
        request.has_horizon, request.horizon = True, 2.0
        request.has_num_intervals, request.num_intervals = True, 5
        request.has_num_elements, request.num_elements = True, 2
        request.target_accuracy = -1.0
        response = self.solve(request)
        solution = response.solution
        print("panda push through the node: status %d, %d Ipopt iterations, %.2f s, puck %.2e "
              "from its target, %d modelled / %d checked pairs"
              % (response.status, solution.statistics.ipopt_iterations,
                 solution.statistics.wall_time, solution.bodies[0].target_distance,
                 len(solution.modeled_pairs), len(solution.checked_pairs)))
        self.assertEqual(response.status, Solution.SUCCESS, response.message)
        self.assertLess(solution.bodies[0].target_distance, 1e-3)
        self.assertGreater(len(solution.checked_pairs), 100)  # lazy: most pairs only checked
        self.assertEqual(len(solution.joint_trajectory.joint_names), 7)
        self.assertAlmostEqual(solution.joint_trajectory.points[0].positions[3], -2.356, places=9)
        # No sphere inside the puck or the table at any element boundary; the checked pairs
        # stay beyond the margin along the whole answer.
        for pair in solution.modeled_pairs:
            self.assertGreaterEqual(pair.min_distance, -1e-9, (pair.first, pair.second))
        for pair in solution.checked_pairs:
            self.assertGreater(pair.min_distance, 0.0, (pair.first, pair.second))
        # Contact and release times per sphere pair: the puck meets a Panda sphere.
        contacts = [e for e in solution.switches if "puck" in (e.first, e.second)]
        self.assertTrue(contacts, solution.switches)
        self.assertTrue(all(e.first.startswith("panda_") and "/sphere_" in e.first
                            for e in contacts), contacts)
        # The puck rests on the table: it slid on it, at its height at every element boundary.
        self.assertEqual(solution.bodies[0].support, "table")
        self.assertTrue(all(p.z == 0.05 for p in solution.bodies[0].positions))
        self.assertNotIn(("puck", "table"), [(p.first, p.second) for p in solution.modeled_pairs])

    def test_the_panda_turns_a_bar_on_the_table_to_a_pose(self):
        # examples/robot_scenes.h, pandaBarTask, through the node's default request (verified, the
        # accuracy ladder): a bar of three spheres on the table moved 12 cm and turned 0.5 rad.
        request = panda_on_the_table(BodySpec(
            name="bar", add=True, initial_position=Point(0.45, 0.0, 0.03),
            sphere_offsets=[Point(-0.05, 0, 0), Point(0, 0, 0), Point(0.05, 0, 0)],
            sphere_radii=[0.03, 0.03, 0.03], turns=True, target=Point(0.55, 0.07, 0.03),
            target_weight=100.0, target_yaw=0.5, target_yaw_weight=100.0))
        request.has_horizon, request.horizon = True, 3.0
        request.has_num_intervals, request.num_intervals = True, 12
        response = self.solve(request)
        solution = response.solution
        print("panda turns a bar through the node: status %d, %d Ipopt iterations, %.2f s, bar "
              "%.2e from its target, yaw %.2e"
              % (response.status, solution.statistics.ipopt_iterations,
                 solution.statistics.wall_time, solution.bodies[0].target_distance,
                 solution.bodies[0].target_yaw_distance))
        self.assertEqual(response.status, Solution.SUCCESS, response.message)
        bar = solution.bodies[0]
        self.assertEqual(bar.support, "table")
        self.assertLess(bar.target_distance, 5e-3)
        self.assertLess(bar.target_yaw_distance, math.radians(2.0))
        self.assertAlmostEqual(bar.yaws[-1], 0.5, delta=math.radians(2.0))
        self.assertTrue(all(abs(p.z - 0.03) < 1e-12 for p in bar.positions))
        for pair in solution.modeled_pairs + solution.checked_pairs:
            self.assertGreaterEqual(pair.min_distance, -1e-9, (pair.first, pair.second))

    def test_supports_that_cannot_hold_a_body_are_refused_and_the_node_keeps_serving(self):
        def puck_request(z, support="", walls=None):
            request = PlanRequest()
            request.urdf = '<robot name="empty"><link name="world"/></robot>'
            request.planar_override, request.planar = True, False
            request.bodies = [
                BodySpec(name="pusher", add=True, radius=0.02, initial_position=Point(-0.2, 0, z),
                         role=BodySpec.ROLE_ACTUATED, max_speed=0.3),
                BodySpec(name="puck", add=True, radius=0.05, initial_position=Point(0, 0, z),
                         target=Point(0.1, 0, z), target_weight=100.0, support=support)]
            request.walls = walls or [Wall(name="table", normal=Vector3(0, 0, 1), offset=0.0)]
            request.has_horizon, request.horizon = True, 2.0
            request.has_num_intervals, request.num_intervals = True, 10
            return request
        self.assert_invalid(puck_request(0.05, "post"), "its support 'post' is no wall")
        lid = Wall(name="lid", normal=Vector3(0, 0, -1), offset=-0.1)
        self.assert_invalid(puck_request(0.05, walls=[
            Wall(name="table", normal=Vector3(0, 0, 1), offset=0.0), lid]),
            "rests on two level walls, 'table' and 'lid'")
        self.assert_invalid(puck_request(0.04), "puck/table overlap at the start")
        self.assert_invalid(puck_request(0.2, "table"), "does not rest on 'table'")
        ramp = Wall(name="ramp", normal=Vector3(0, 0.6, 0.8), offset=0.0)
        self.assert_invalid(puck_request(0.05, "ramp", walls=[ramp]), "a support must be level")
        # "none" lets it float: the pair with the table is modelled instead.
        floating = self.solve(puck_request(0.05, "none"))
        self.assertIn(floating.status, [Solution.SUCCESS, Solution.ACCURACY_NOT_MET],
                      floating.message)
        self.assertEqual(floating.solution.bodies[1].support, "")
        self.assertIn(("puck", "table"),
                      [(p.first, p.second) for p in floating.solution.modeled_pairs])
        resting = self.solve(puck_request(0.05))
        self.assertEqual(resting.status, Solution.SUCCESS, resting.message)
        self.assertEqual(resting.solution.bodies[1].support, "table")

    def test_a_replan_warm_starts_from_the_last_robot_plan_or_says_why_not(self):
        first = self.solve(arm_push_request())
        self.assertEqual(first.status, Solution.SUCCESS, first.message)
        moved = arm_push_request()
        moved.bodies[0].target = Point(0.6, 0.21, 0.0)
        moved.warm_start = True
        warm = self.solve(moved)
        statistics = warm.solution.statistics
        print("planar arm push replanned 1 cm: %d Ipopt iterations warm, %d for the first plan"
              % (statistics.ipopt_iterations, first.solution.statistics.ipopt_iterations))
        self.assertEqual(warm.status, Solution.SUCCESS, warm.message)
        self.assertTrue(statistics.warm_started, warm.message)
        self.assertEqual(statistics.start, "previous solution")
        self.assertEqual(statistics.nlp_variables, first.solution.statistics.nlp_variables)
        self.assertLess(statistics.ipopt_iterations,
                        first.solution.statistics.ipopt_iterations / 2)
        self.assertLess(warm.solution.bodies[0].target_distance, 1e-3)
        self.assertLess(warm.solution.verification_error, 1e-3)
        longer = moved
        longer.horizon = 2.5
        cold = self.solve(longer)
        self.assertEqual(cold.status, Solution.SUCCESS, cold.message)
        self.assertFalse(cold.solution.statistics.warm_started)
        self.assertEqual(cold.solution.statistics.start, "robot guess")
        self.assertIn("cold start: the horizons differ: 2 -> 2.5", cold.message)

    def test_a_robot_goal_reports_every_relaxed_nlp_and_stops_when_cancelled(self):
        client = actionlib.SimpleActionClient(PLAN, PlanTrajectoryAction)
        self.assertTrue(client.wait_for_server(rospy.Duration(60.0)), "no ~plan action server")
        request = arm_push_request()
        request.target_accuracy = 1e-14  # no rung reaches it: the ladder runs for seconds
        feedback = []
        client.send_goal(PlanTrajectoryGoal(request=request), feedback_cb=feedback.append)
        deadline = time.time() + 60.0
        while not feedback and time.time() < deadline:
            time.sleep(0.01)
        self.assertTrue(feedback, "no feedback")
        self.assertEqual(feedback[0].homotopy_step, 1)
        cancelled_at = time.time()
        client.cancel_goal()
        self.assertTrue(client.wait_for_result(rospy.Duration(10.0)))
        self.assertLess(time.time() - cancelled_at, 2.0)
        self.assertEqual(client.get_state(), GoalStatus.PREEMPTED)
        result = client.get_result()
        self.assertEqual(result.status, Solution.CANCELLED, result.message)
        points = result.solution.joint_trajectory.points
        self.assertTrue(points)
        self.assertTrue(all(math.isfinite(q) for p in points for q in p.positions))

    def test_allowed_pairs_may_name_links_and_keep_the_other_pairs_out(self):
        request = arm_push_request()
        request.allowed_pairs = [ContactPair(first="disc", second="hand")]
        response = self.solve(request)
        self.assertEqual(response.status, Solution.SUCCESS, response.message)
        solution = response.solution
        self.assertTrue(solution.modeled_pairs)
        for pair in solution.modeled_pairs:
            self.assertTrue(pair.first.startswith("hand/sphere_"), pair.first)
            self.assertEqual(pair.second, "disc")
        excluded = [p for p in solution.pruned_pairs if p.reason == "not among the allowed pairs"]
        self.assertIn("forearm", {p.first.split("/")[0] for p in excluded})
        self.assertLess(solution.bodies[0].target_distance, 1e-3)
        request.allowed_pairs = [ContactPair(first="disc", second="no_such_link")]
        self.assert_invalid(request, "allowed pair disc/no_such_link names no pair")

    def test_a_passive_joint_is_never_commanded_and_turns_only_when_pushed(self):
        request = arm_push_request()
        request.joints.append(JointSpec(name="wrist", role=BodySpec.ROLE_PASSIVE))
        response = self.solve(request)
        self.assertEqual(response.status, Solution.SUCCESS, response.message)
        solution = response.solution
        self.assertLess(solution.bodies[0].target_distance, 1e-3)
        wrist = JOINTS.index("wrist")
        self.assertTrue(all(p.velocities[wrist] == 0.0 for p in solution.joint_commands.points))
        angles = [p.positions[wrist] for p in solution.joint_trajectory.points]
        contact = min(s.time for s in solution.switches if s.kind == s.CONTACT)
        before = [q for q, t in zip(angles, solution.times) if t <= contact + 1e-9]
        self.assertLess(max(abs(q) for q in before), 1e-9)  # still until the hand meets the disc
        self.assertGreater(max(abs(q) for q in angles), 1e-3)  # then the push turns it

    def test_joint_settings_are_checked(self):
        request = arm_push_request()
        request.joints.append(JointSpec(name="knee"))
        self.assert_invalid(request, "joint 'knee'", "shoulder, elbow, wrist")
        request = arm_push_request()
        request.joints.append(JointSpec(name="elbow", max_velocity=float("nan")))
        self.assert_invalid(request, "joint 'elbow'", "NaN")
        request = arm_push_request()
        request.joints.append(JointSpec(name="elbow", has_bounds=True, lower=0.1, upper=1.0))
        self.assert_invalid(request, "joint 'elbow' starts at 0, outside its bounds")
        request = arm_push_request()
        request.joints.append(JointSpec(name="wrist", role=BodySpec.ROLE_PASSIVE, max_velocity=1.0))
        self.assert_invalid(request, "joint 'wrist' is passive: it takes no max_velocity")
        request = arm_push_request()
        request.bodies[0].add = False
        self.assert_invalid(request, "body 'disc'")

    def test_a_missing_or_broken_srdf_is_refused_and_the_node_keeps_serving(self):
        request = arm_push_request()
        request.self_collision, request.srdf_param = True, "/no/such/srdf"
        self.assert_invalid(request, "no parameter '/no/such/srdf' holds an SRDF")
        rospy.set_param("/broken_srdf", '<robot name="arm"><disable_collisions link1="hand"')
        request.srdf_param = "/broken_srdf"
        self.assert_invalid(request, "SRDF '/broken_srdf': malformed SRDF")
        rospy.set_param("/srdf_without_robot", "<group/>")
        request.srdf_param = "/srdf_without_robot"
        self.assert_invalid(request, "malformed SRDF: no <robot> element")
        response = self.solve(arm_push_request())
        self.assertEqual(response.status, Solution.SUCCESS, response.message)

    def test_a_joint_turns_at_its_commanded_speed(self):
        request = SimulateRequest()
        request.urdf_param = ARM
        request.has_horizon, request.horizon = True, 1.0
        request.has_num_steps, request.num_steps = True, 4
        request.joint_commands.joint_names = ["elbow"]
        request.joint_commands.points = [JointTrajectoryPoint(velocities=[0.7])]
        response = self.simulate(request)
        self.assertEqual(response.status, Solution.SUCCESS, response.message)
        end = response.solution.joint_trajectory.points[-1].positions
        self.assertAlmostEqual(end[1], 0.7, delta=1e-9)
        self.assertAlmostEqual(end[0], 0.0, delta=1e-12)
        self.assertAlmostEqual(end[2], 0.0, delta=1e-12)
        self.assertAlmostEqual(response.solution.joint_trajectory.points[-1].velocities[1], 0.7,
                               delta=1e-9)
        request.joint_commands.joint_names = ["knee"]
        response = self.simulate(request)
        self.assertEqual(response.status, Solution.INVALID_REQUEST)
        self.assertIn("'knee'", response.message)

    def test_commands_name_what_the_scene_has_or_are_refused(self):
        # One request path for discs and robots: body commands in a robot scene are read as in a
        # scene of discs, joint commands without a robot are refused, and the node keeps serving.
        request = SimulateRequest()
        request.urdf_param = ARM
        request.has_horizon, request.horizon = True, 1.0
        request.has_num_steps, request.num_steps = True, 4
        request.bodies = [BodySpec(name="pusher", add=True, radius=0.05, role=BodySpec.ROLE_ACTUATED,
                                   initial_position=Point(x=0.0, y=-0.8), max_speed=1.0)]
        request.commands = [BodyTrajectory(name="pusher", controls=[Vector3(x=0.3)])]
        response = self.simulate(request)
        self.assertEqual(response.status, Solution.SUCCESS, response.message)
        self.assertAlmostEqual(response.solution.bodies[0].positions[-1].x, 0.3, delta=1e-9)
        for name in ["hand/sphere_0", "hand", "no_such_body"]:
            request.commands = [BodyTrajectory(name=name, controls=[Vector3(x=0.3)])]
            response = self.simulate(request)
            self.assertEqual(response.status, Solution.INVALID_REQUEST, name)
            self.assertIn("not an actuated body", response.message)
        request.commands = [BodyTrajectory(name="pusher", controls=[Vector3(x=float("nan"))])]
        response = self.simulate(request)
        self.assertEqual(response.status, Solution.INVALID_REQUEST)
        self.assertIn("not finite", response.message)
        discs = SimulateRequest()
        discs.joint_commands.joint_names = ["elbow"]
        discs.joint_commands.points = [JointTrajectoryPoint(velocities=[0.7])]
        response = self.simulate(discs)
        self.assertEqual(response.status, Solution.INVALID_REQUEST)
        self.assertIn("joint_commands are given, but the scene has no robot", response.message)
        request.commands = []
        self.assertEqual(self.simulate(request).status, Solution.SUCCESS)


if __name__ == "__main__":
    rostest.rosrun("fesd_trajopt", "robot_node", RobotNodeTest)
