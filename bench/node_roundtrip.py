#!/usr/bin/python3
"""Service round trip and peak memory of a running fesd_trajopt node, per scene.

Start the node first (roslaunch fesd_trajopt fesd_trajopt.launch), or use
bench/node_roundtrip.sh, which does both. Prints one line of key=value pairs per run. The node's
peak resident memory (VmHWM) only grows, so run the cases in the order of interest.
"""
import argparse
import random
import statistics
import sys
import threading
import time
import xmlrpc.client

import rosgraph
import rospy
from fesd_trajopt.msg import BodySpec, Obstacle, PlanRequest
from fesd_trajopt.srv import SolveTrajectory
from geometry_msgs.msg import Point

NODE = "/fesd_trajopt"


def passive_disc(name, x, y, radius):
    body = BodySpec(name=name, add=True, radius=radius, role=BodySpec.ROLE_PASSIVE)
    body.initial_position.x, body.initial_position.y = x, y
    return body


def default_scene():
    return PlanRequest()


def default_unverified():
    """The default scene without the verification of the default accuracy target."""
    request = PlanRequest()
    request.target_accuracy = -1.0
    return request


def far_body():
    """The default scene and one disc far out of reach: its pairs are pruned."""
    request = PlanRequest()
    request.bodies = [passive_disc("far_away", 1e4, 1e4, 1.0)]
    return request


def ten_discs_out_of_reach():
    """The default scene and seven passive discs beyond the actuators' reach."""
    request = PlanRequest()
    request.bodies = [passive_disc("rock_%d" % i, 150.0 + 5.0 * i, 0.0, 1.0) for i in range(7)]
    return request


def ten_discs_in_reach():
    """The default scene and seven passive discs the actuators could reach (no target of
    theirs, off the pushing path): every pair that can touch is modelled."""
    request = PlanRequest()
    request.bodies = [passive_disc("rock_%d" % i, -12.0 + 4.0 * i, -12.0, 1.0) for i in range(7)]
    return request


def ten_discs_in_reach_all_pairs():
    """ten_discs_in_reach with every pair in reach modelled from the start (before lazy pairs)."""
    request = ten_discs_in_reach()
    request.contact_pairs = PlanRequest.PAIRS_ALL_IN_REACH
    return request


def disc_in_the_way():
    """The default scene and a passive disc (radius 1) at (0, 6), in the object's way."""
    request = PlanRequest()
    request.bodies = [passive_disc("in_the_way", 0.0, 6.0, 1.0)]
    return request


def disc_in_the_way_to_1e_2():
    """disc_in_the_way with target_accuracy 1e-2: the ladder refines until the plan verifies."""
    request = disc_in_the_way()
    request.target_accuracy = 1e-2
    return request


def largest_allowed():
    """27 passive discs near the actuators on the finest grid the limits allow (200 intervals x 6
    elements x 4 stages) with a 30 s budget: the node's peak memory on its largest request."""
    request = PlanRequest()
    request.bodies = [passive_disc("rock_%d" % i, -13.0 + 2.6 * (i % 9), -12.0 - 3.0 * (i // 9),
                                   0.8) for i in range(27)]
    request.has_num_intervals, request.num_intervals = True, 200
    request.has_num_elements, request.num_elements = True, 6
    request.has_num_stages, request.num_stages = True, 4
    request.has_wall_time_budget, request.wall_time_budget = True, 30.0
    return request


def object_target(x, y):
    request = PlanRequest()
    body = BodySpec(name="object", target_weight=1000.0)
    body.target.x, body.target.y = x, y
    request.bodies = [body]
    return request


def target_inside_a_disc():
    """The object's target (0, 10) inside a fixed disc of radius 3 at (0, 9)."""
    request = PlanRequest()
    request.obstacles = [Obstacle(name="rock", radius=3.0, position=Point(0.0, 9.0, 0.0))]
    return request


CASES = {"default": default_scene, "default_unverified": default_unverified,
         "far_body": far_body, "largest_allowed": largest_allowed,
         "ten_discs_out_of_reach": ten_discs_out_of_reach, "ten_discs_in_reach": ten_discs_in_reach,
         "ten_discs_in_reach_all_pairs": ten_discs_in_reach_all_pairs,
         "disc_in_the_way": disc_in_the_way, "disc_in_the_way_to_1e-2": disc_in_the_way_to_1e_2,
         # Soft targets out of the actuators' reach (their workspace bounds) or inside a body.
         "target_x_0.9": lambda: object_target(0.9, 10.0),
         "target_x_-0.9": lambda: object_target(-0.9, 10.0),
         "target_x_1.2": lambda: object_target(1.2, 10.0),
         "target_inside_a_disc": target_inside_a_disc}


def node_memory_mib():
    uri = rosgraph.Master("/fesd_trajopt_roundtrip_bench").lookupNode(NODE)
    pid = xmlrpc.client.ServerProxy(uri).getPid("/")[2]
    fields = dict(line.split(":", 1) for line in open("/proc/%d/status" % pid))
    return (int(fields["VmHWM"].split()[0]) / 1024.0, int(fields["VmRSS"].split()[0]) / 1024.0)


def describe(case, run, response, round_trip):
    stats = response.solution.statistics
    peak, resident = node_memory_mib()
    missed = [b.target_distance for b in response.solution.bodies
              if b.target_distance == b.target_distance]  # NaN: no target
    print("case=%s run=%d status=%d bodies=%d modelled_pairs=%d checked_pairs=%d "
          "pruned_pairs=%d pair_rounds=%d nlp_variables=%d complementarities=%d "
          "ipopt_iterations=%d objective=%.7g warm_started=%d rungs=%d solve_s=%.3f "
          "round_trip_s=%.3f verification_error=%.3g target_distance=%.3g node_peak_mib=%.1f "
          "node_rss_mib=%.1f" % (
              case, run, response.status, len(response.solution.bodies),
              len(response.solution.modeled_pairs), len(response.solution.checked_pairs),
              len(response.solution.pruned_pairs), stats.pair_rounds,
              stats.nlp_variables, stats.complementarity_constraints,
              stats.ipopt_iterations, stats.objective, stats.warm_started,
              len(response.solution.refinements), stats.wall_time, round_trip,
              response.solution.verification_error if response.solution.verified
              else float("nan"), max(missed, default=float("nan")), peak, resident))
    sys.stdout.flush()


def warm_sequence(solve, count, seed):
    """A cold default request, then `count` warm ones, each moving the object's target to a
    random x within 0.3 of the default's (seeded); prints each and the medians."""
    rng = random.Random(seed)
    started = time.monotonic()
    cold = solve(PlanRequest())
    cold_s = time.monotonic() - started
    describe("cold", 0, cold, cold_s)
    times, successes, warm = [], 0, 0
    for run in range(count):
        request = object_target(rng.uniform(-0.3, 0.3), 10.0)
        request.warm_start = True
        started = time.monotonic()
        response = solve(request)
        round_trip = time.monotonic() - started
        describe("warm", run, response, round_trip)
        times.append(round_trip)
        successes += response.status == 0
        warm += response.solution.statistics.warm_started
    print("warm_sequence requests=%d success=%d warm_started=%d median_round_trip_s=%.3f "
          "max_round_trip_s=%.3f cold_round_trip_s=%.3f median_over_cold=%.3f" % (
              count, successes, warm, statistics.median(times), max(times), cold_s,
              statistics.median(times) / cold_s))


def together(count, cases):
    """`count` requests of the cases (cycled) sent at once, each on its own connection, then the
    same one after the other: wall times and whether the answers are identical. Each case is
    solved once before, so that neither pass pays the node's first-request costs."""
    requests = [CASES[cases[i % len(cases)]]() for i in range(count)]
    answers = [None] * count
    warm_up = rospy.ServiceProxy(NODE + "/solve_trajectory", SolveTrajectory)
    for request in requests[:len(cases)]:
        warm_up(request)

    def call(i):
        answers[i] = rospy.ServiceProxy(NODE + "/solve_trajectory", SolveTrajectory)(requests[i])

    threads = [threading.Thread(target=call, args=(i,)) for i in range(count)]
    started = time.monotonic()
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    at_once = time.monotonic() - started
    solve = rospy.ServiceProxy(NODE + "/solve_trajectory", SolveTrajectory)
    started = time.monotonic()
    alone = [solve(request) for request in requests]
    in_sequence = time.monotonic() - started
    identical = sum(a.status == b.status and a.solution.states == b.solution.states and
                    a.solution.statistics.ipopt_iterations == b.solution.statistics.ipopt_iterations
                    for a, b in zip(answers, alone))
    print("together requests=%d cases=%s at_once_s=%.3f in_sequence_s=%.3f ratio=%.3f "
          "identical=%d statuses=%s" % (count, ",".join(cases), at_once, in_sequence,
                                        at_once / in_sequence, identical,
                                        ",".join(str(a.status) for a in answers)))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", default="default,far_body,ten_discs_out_of_reach",
                        help="comma-separated, from: " + ", ".join(CASES))
    parser.add_argument("--repeat", type=int, default=1, help="runs of each case (of --together)")
    parser.add_argument("--verify", action="store_true", help="set verify in every request")
    parser.add_argument("--warm-sequence", type=int, default=0,
                        help="then a cold default request and this many warm replans")
    parser.add_argument("--together", type=int, default=0,
                        help="then this many requests of --cases at once, and in sequence")
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args(rospy.myargv()[1:])
    rospy.init_node("fesd_trajopt_roundtrip_bench", anonymous=True)
    rospy.wait_for_service(NODE + "/solve_trajectory", timeout=60.0)
    solve = rospy.ServiceProxy(NODE + "/solve_trajectory", SolveTrajectory)
    cases = args.cases.split(",") if args.cases else []
    if args.together:
        for _ in range(args.repeat):
            together(args.together, cases)
        return 0
    for case in cases:
        for run in range(args.repeat):
            started = time.monotonic()
            request = CASES[case]()
            request.verify = args.verify
            response = solve(request)
            describe(case, run, response, time.monotonic() - started)
    if args.warm_sequence:
        warm_sequence(solve, args.warm_sequence, args.seed)
    return 0


if __name__ == "__main__":
    sys.exit(main())
