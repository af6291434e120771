#!/usr/bin/env python3
"""Least-squares convergence orders from `fesd_bench order-pds` / `order-filippov` CSV (stdin or
a file).

For each (method, scheme, n_s): slope of log(error) against log(h) over the converged runs, from the
coarsest grid down to the round-off plateau: a run is left out, with all finer ones, once its
error is below the floor (default 1e-12), or below the plateau level (default 1e-9) without
improving on the coarser run. Larger errors are all kept, even where they do not decrease
monotonically (the standard method's error depends on where switches fall in an element).
`--from-total FAMILY:N_S=TOTAL` leaves out that scheme's runs on coarser grids than TOTAL
elements (pre-asymptotic ones, e.g. implicit Euler damping the spiral of Nurkanovic et al. 2024).
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


def family(scheme):
    """The collocation family of a scheme column ("radau_iia", "gauss_legendre_2", ...)."""
    return scheme.rstrip("0123456789_")


def expected_order(scheme, stages):
    """The order FESD recovers: the RK order of the scheme."""
    return 2 * stages if family(scheme) == "gauss_legendre" else 2 * stages - 1


def fitted_orders(rows, floor=1e-12, plateau=1e-9, from_total=None):
    """{(method, family, n_s): (order, points used)} from order CSV rows (dicts);
    from_total: {(family, n_s): smallest n_fe_total used}."""
    from_total = from_total or {}
    runs = defaultdict(list)
    for row in rows:
        coarsest = from_total.get((family(row["scheme"]), int(row["n_s"])), 0)
        if row["status"] == "ok" and int(row["n_fe_total"]) >= coarsest:
            key = (row["method"], family(row["scheme"]), int(row["n_s"]))
            runs[key].append((float(row["h"]), float(row["error"])))
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
    parser.add_argument("--from-total", action="append", default=[], metavar="FAMILY:N_S=TOTAL")
    args = parser.parse_args()
    from_total = {}
    for item in args.from_total:
        scheme, total = item.split("=")
        name, stages = scheme.split(":")
        from_total[(name, int(stages))] = int(total)
    orders = fitted_orders(csv.DictReader(args.csv), args.floor, args.plateau, from_total)
    print("method,scheme,n_s,points,fitted_order,expected_fesd_order")
    for (method, scheme, stages), (order, points) in sorted(orders.items()):
        print(f"{method},{scheme},{stages},{points},{order:.2f},{expected_order(scheme, stages)}")


if __name__ == "__main__":
    main()
