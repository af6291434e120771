#!/usr/bin/python3
"""Integration tests of the node's interactive targets (~targets): feedback published as rviz
does, the plans it starts, hostile feedback."""
import math
import threading
import time
import unittest

import rospy
import rostest
from fesd_trajopt.msg import BodySpec, PlanRequest, Solution
from fesd_trajopt.srv import SolveTrajectory
from visualization_msgs.msg import (InteractiveMarkerFeedback, InteractiveMarkerInit,
                                   InteractiveMarkerUpdate)

SOLVE = "/fesd_trajopt/solve_trajectory"
TARGETS = "/fesd_trajopt/targets"
CLIENT = "/rviz/InteractiveMarkers"  # the server takes one client's feedback at a time


def feedback(name, x, y, event=InteractiveMarkerFeedback.MOUSE_UP, menu_entry=0):
    f = InteractiveMarkerFeedback()
    f.menu_entry_id = menu_entry  # 1 Plan, 2 Execute with feedback, 3 Reset targets
    f.header.frame_id = "world"
    f.client_id = CLIENT
    f.marker_name = name
    f.event_type = event
    f.pose.position.x, f.pose.position.y = x, y
    f.pose.orientation.w = 1.0
    return f


class InteractiveTargetsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_interactive_targets", anonymous=True)
        rospy.wait_for_service(SOLVE, timeout=60.0)
        cls.solve = rospy.ServiceProxy(SOLVE, SolveTrajectory)
        cls.lock = threading.Lock()
        cls.solutions = []  # (arrival time, Solution), the latched one included
        cls.markers = None
        rospy.Subscriber("/fesd_trajopt/solution", Solution, cls.received)
        rospy.Subscriber(TARGETS + "/update_full", InteractiveMarkerInit, cls.initial_markers)
        cls.poses = {}  # the last pose the server published per marker
        rospy.Subscriber(TARGETS + "/update", InteractiveMarkerUpdate, cls.updated)
        cls.feedback = rospy.Publisher(TARGETS + "/feedback", InteractiveMarkerFeedback,
                                       queue_size=2000)
        deadline = time.time() + 30.0
        while cls.feedback.get_num_connections() == 0 and time.time() < deadline:
            time.sleep(0.05)

    @classmethod
    def received(cls, solution):
        with cls.lock:
            cls.solutions.append((time.time(), solution))

    @classmethod
    def updated(cls, update):
        for pose in update.poses:
            cls.poses[pose.name] = pose.pose.position

    @classmethod
    def initial_markers(cls, init):
        cls.markers = init

    def solutions_since(self, since):
        with self.lock:
            return [s for t, s in self.solutions if t >= since]

    def wait_for_solutions(self, since, count, timeout):
        deadline = time.time() + timeout
        while len(self.solutions_since(since)) < count and time.time() < deadline:
            time.sleep(0.02)
        return self.solutions_since(since)

    def wait_until_quiet(self, since, quiet, timeout):
        """The solutions since `since` once none came for `quiet` seconds."""
        deadline = time.time() + timeout
        while time.time() < deadline:
            with self.lock:
                last = self.solutions[-1][0] if self.solutions else 0.0
            if time.time() - max(last, since) > quiet:
                break
            time.sleep(0.1)
        return self.solutions_since(since)

    def settled(self):
        """Now, once the solutions of requests already answered have arrived (a loaded machine
        delivered a cold request's after the next drag had started): the start of a count. Quiet
        from now on: a service's answer can come before its published solution, which counted as
        the next drag's when none had arrived yet."""
        self.wait_until_quiet(time.time(), 0.5, 30.0)
        return time.time()

    def object_end(self, solution):
        (body,) = [b for b in solution.bodies if b.name == "object"]
        return body.positions[-1]

    def test_1_the_default_scene_has_a_marker_per_body_with_a_target(self):
        deadline = time.time() + 30.0
        while self.markers is None and time.time() < deadline:
            time.sleep(0.05)
        self.assertIsNotNone(self.markers, "no " + TARGETS + "/update_full")
        by_name = {m.name: m for m in self.markers.markers}
        self.assertEqual(sorted(by_name), ["actuator_1", "actuator_2", "object"])
        self.assertEqual(by_name["object"].header.frame_id, "world")
        self.assertAlmostEqual(by_name["object"].pose.position.y, 10.0)
        self.assertEqual([c.name for c in by_name["object"].controls], ["move"])
        self.assertEqual(by_name["object"].controls[0].interaction_mode,
                         by_name["object"].controls[0].MOVE_PLANE)
        self.assertEqual([e.title for e in by_name["object"].menu_entries],
                         ["Plan", "Execute with feedback", "Reset targets"])

    def release(self, x, y):
        """Releases `object` at (x, y); its solution and the seconds until it came."""
        since = self.settled()
        self.feedback.publish(feedback("object", x, y))
        self.assertTrue(self.wait_for_solutions(since, 1, 120.0), "no solution")
        with self.lock:
            arrival, solution = [(t, s) for t, s in self.solutions if t >= since][0]
        return solution, arrival - since

    def test_2a_a_released_target_is_planned_warm_sooner_than_a_cold_request(self):
        cold = self.solve(PlanRequest())
        self.assertEqual(cold.status, Solution.SUCCESS, cold.message)
        cold_time = cold.solution.statistics.wall_time
        solution, elapsed = self.release(0.4, 9.5)
        end = self.object_end(solution)
        rospy.loginfo("release -> solution: %.3f s (solve %.3f s, %s), cold default request "
                      "%.3f s", elapsed, solution.statistics.wall_time,
                      "warm" if solution.statistics.warm_started else "cold", cold_time)
        self.assertEqual(solution.status, Solution.SUCCESS, solution.message)
        self.assertLess(math.hypot(end.x - 0.4, end.y - 9.5), 1e-2)
        self.assertTrue(solution.statistics.warm_started)
        self.assertLess(elapsed, cold_time)

    def test_2b_a_target_out_of_the_pushers_reach_is_planned_to_the_nearest_end(self):
        # actuator_1 stays at x <= -2.5 (its workspace), radii 1 + 2: it pushes the object to
        # x <= 0.5 at most, so (1.0, 9.5) is answered as out of reach, not as a success.
        solution, _ = self.release(1.0, 9.5)
        end = self.object_end(solution)
        self.assertEqual(solution.status, Solution.TARGET_NOT_REACHED, solution.message)
        self.assertIn("out of the pushers' reach", solution.message)
        self.assertLess(end.x, 0.5 + 1e-2)
        self.assertGreater(end.y, 9.0)

    def test_3_hostile_feedback_is_refused_without_a_solve(self):
        # A request whose actuator_2 has no target: it has no marker.
        request = PlanRequest(bodies=[BodySpec(name="actuator_2", clear_target=True)])
        answer = self.solve(request)
        self.assertNotEqual(answer.status, Solution.INVALID_REQUEST, answer.message)
        since = self.settled()
        for f in [feedback("no_such_body", 1.0, 9.0), feedback("object", float("nan"), 9.0),
                  feedback("object", 1.0, float("inf")), feedback("object", 1e12, 9.0),
                  feedback("object", 1.0, -1e12), feedback("actuator_2", 5.0, 0.0),
                  feedback("actuator_1", 0.0, 0.0),  # beyond its workspace bound x <= -2.5
                  feedback("object", 1.0, 9.0, InteractiveMarkerFeedback.POSE_UPDATE)]:
            self.feedback.publish(f)
        time.sleep(3.0)
        self.assertEqual(self.solutions_since(since), [])
        self.assertEqual(self.solve(request).status, answer.status)

    def test_4_a_flood_of_feedback_runs_at_most_two_solves(self):
        answer = self.solve(PlanRequest())
        self.assertEqual(answer.status, Solution.SUCCESS, answer.message)
        since = self.settled()
        rate = rospy.Rate(2040)
        for k in range(1020):  # 1000 drags and 20 releases in about half a second
            release = k % 51 == 50
            self.feedback.publish(feedback(
                "object", 0.3 * math.sin(k / 100.0), 9.5,
                InteractiveMarkerFeedback.MOUSE_UP if release
                else InteractiveMarkerFeedback.POSE_UPDATE))
            rate.sleep()
        flooded = time.time() - since
        solutions = self.wait_until_quiet(since, 10.0, 180.0)
        rospy.loginfo("flood of %.2f s: %d solve(s)", flooded, len(solutions))
        self.assertLess(flooded, 1.0)  # within the solves' spacing
        self.assertGreaterEqual(len(solutions), 1)
        self.assertLessEqual(len(solutions), 2)
        for solution in solutions:
            self.assertEqual(solution.status, Solution.SUCCESS, solution.message)
        again = self.solve(PlanRequest())
        self.assertEqual(again.status, Solution.SUCCESS, again.message)

    def execute_towards(self, x, y):
        """Drags `object` to (x, y), chooses Execute with feedback: the plan and the execution."""
        self.feedback.publish(feedback("object", x, y, InteractiveMarkerFeedback.POSE_UPDATE))
        time.sleep(0.3)
        since = self.settled()
        self.feedback.publish(
            feedback("object", x, y, InteractiveMarkerFeedback.MENU_SELECT, menu_entry=2))
        return self.wait_for_solutions(since, 2, 120.0)[:2]

    def test_5_the_menu_executes_with_feedback_and_resets(self):
        answer = self.solve(PlanRequest())
        self.assertEqual(answer.status, Solution.SUCCESS, answer.message)
        time.sleep(1.0)  # the solves' spacing after the flood
        menu = InteractiveMarkerFeedback.MENU_SELECT
        plan, executed = self.execute_towards(0.3, 8.0)
        self.assertEqual(plan.status, Solution.SUCCESS, plan.message)
        self.assertIn("executed with feedback", executed.message)
        self.assertEqual(executed.status, Solution.SUCCESS, executed.message)  # targets judged
        end = self.object_end(executed)
        self.assertLess(math.hypot(end.x - 0.3, end.y - 8.0), 1e-2)
        # Reset: the marker back at the request's target, without a solve.
        since = self.settled()
        self.feedback.publish(feedback("object", 0.3, 8.0, menu, menu_entry=3))
        deadline = time.time() + 10.0
        while time.time() < deadline and abs(self.poses.get("object", end).y - 10.0) > 1e-9:
            time.sleep(0.05)
        self.assertAlmostEqual(self.poses["object"].y, 10.0)
        time.sleep(1.0)
        self.assertEqual(self.solutions_since(since), [])
        # Executed towards a target out of reach: the execution says it missed.
        plan, executed = self.execute_towards(1.0, 9.5)
        self.assertEqual(plan.status, Solution.TARGET_NOT_REACHED, plan.message)
        self.assertEqual(executed.status, Solution.TARGET_NOT_REACHED, executed.message)


if __name__ == "__main__":
    rostest.rosrun("fesd_trajopt", "interactive_targets", InteractiveTargetsTest)
