#!/usr/bin/env python3
"""Least-squares convergence orders from `fesd_bench order-pds` CSV (stdin or a file).

For each (method, n_s): slope of log(error) against log(h) over the converged runs, from the
coarsest grid down to the round-off plateau: a run is left out, with all finer ones, once its
error is below the floor (default 1e-12), or below the plateau level (default 1e-9) without
improving on the coarser run. Larger errors are all kept, even where they do not decrease
monotonically (the standard method's error depends on where switches fall in an element).
"""
import argparse
import csv
import math
import sys
from collections import defaultdict


def fit(points):
    xs = [math.log(h) for h, _ in points]
    ys = [math.log(e) for _, e in points]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    sxx = sum((x - mx) ** 2 for x in xs)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx


def fitted_orders(rows, floor=1e-12, plateau=1e-9):
    """{(method, n_s): (order, points used)} from order-pds CSV rows (dicts)."""
    runs = defaultdict(list)
    for row in rows:
        if row["status"] == "ok":
            runs[(row["method"], int(row["n_s"]))].append((float(row["h"]), float(row["error"])))
    orders = {}
    for key, points in runs.items():
        kept = []
        for h, error in sorted(points, reverse=True):
            stalled = kept and error >= kept[-1][1] and error < plateau
            if error <= floor or stalled:
                break
            kept.append((h, error))
        orders[key] = (fit(kept) if len(kept) >= 2 else float("nan"), len(kept))
    return orders


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("csv", nargs="?", type=argparse.FileType("r"), default=sys.stdin)
    parser.add_argument("--floor", type=float, default=1e-12)
    parser.add_argument("--plateau", type=float, default=1e-9)
    args = parser.parse_args()
    orders = fitted_orders(csv.DictReader(args.csv), args.floor, args.plateau)
    print("method,n_s,points,fitted_order,expected_fesd_order")
    for (method, stages), (order, points) in sorted(orders.items()):
        print(f"{method},{stages},{points},{order:.2f},{2 * stages - 1}")


if __name__ == "__main__":
    main()
