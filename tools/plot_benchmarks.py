#!/usr/bin/python3
"""Plots the benchmark CSVs of docs/benchmarks/ into PNGs beside them (matplotlib, Agg).

Usage: plot_benchmarks.py [directory]. Reads what exists of order_pds.csv, siconos_example1.csv,
ocp_accuracy.csv, scaling.csv, order_filippov.csv, ocp_filippov.csv, sensitivity_sweep.csv,
sensitivity_order.csv, sweep_accuracy.csv and push_t_trajectory.csv; a missing file skips its
plots.
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fit_orders import family, fitted_orders  # noqa: E402

STAGE_COLORS = {1: "tab:blue", 2: "tab:orange", 3: "tab:green", 4: "tab:red"}
# Implicit Euler damps example (47)'s spiral on coarse grids: its order is fitted from 256 on.
FILIPPOV_ASYMPTOTIC_FROM = {("radau_iia", 1): 256}


def read(directory, name):
    path = os.path.join(directory, name)
    if not os.path.exists(path):
        print("plot_benchmarks: no %s, its plots are skipped" % path)
        return []
    with open(path) as f:
        return list(csv.DictReader(f))


def ok(rows):
    return [r for r in rows if r["status"] in ("ok", "success") and float(r["error"]) > 0]


def series(rows, key):
    """Rows grouped by key(row), each group sorted by its first column of interest later."""
    groups = {}
    for row in rows:
        groups.setdefault(key(row), []).append(row)
    return groups


def save_with_grids(figure, axes, directory, name):
    """Every axis gridded, with its legend; then save()."""
    for axis in axes:
        axis.grid(True, which="both", alpha=0.3)
        axis.legend(fontsize=7)
    save(figure, directory, name)


def save(figure, directory, name):
    path = os.path.join(directory, name)
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    plt.close(figure)
    print("plot_benchmarks: wrote " + path)


def plot_orders(axes, order_rows, from_total=None):
    """Error vs h on axes[0] and, if given, error vs CPU time on axes[1], per method and scheme."""
    orders = fitted_orders(order_rows, from_total=from_total)
    key = lambda r: (r["method"], family(r["scheme"]), int(r["n_s"]))  # noqa: E731
    for (method, scheme, n_s), group in sorted(series(ok(order_rows), key).items()):
        group.sort(key=lambda r: float(r["h"]))
        style = ("-" if method == "fesd" else "--") + ("o" if scheme == "radau_iia" else "^")
        name = "%s %s n_s=%d" % (method, scheme, n_s)
        color = STAGE_COLORS.get(n_s)
        axes[0].loglog([float(r["h"]) for r in group], [float(r["error"]) for r in group], style,
                       color=color, markersize=4,
                       label="%s (order %.2f)" % (name, orders[(method, scheme, n_s)][0]))
        if len(axes) > 1:
            axes[1].loglog([float(r["cpu_s"]) for r in group], [float(r["error"]) for r in group],
                           style, color=color, label=name, markersize=4)


def plot_example1(directory, order_rows, peer_rows):
    figure, axes = plt.subplots(1, 2, figsize=(12, 5))
    plot_orders(axes, order_rows)
    for method, group in sorted(series(ok(peer_rows), lambda r: r["method"]).items()):
        group.sort(key=lambda r: float(r["cpu_s"]))
        axes[1].loglog([float(r["cpu_s"]) for r in group], [float(r["error"]) for r in group],
                       ":^", color="black" if "0.5" in method else "gray", label=method,
                       markersize=4)
    axes[0].set(xlabel="h = T / N_FE", ylabel="terminal error |x(T) - (-1, 0)|",
                title="Example 1: error vs step (Radau-IIA)")
    axes[1].set(xlabel="CPU time [s]", ylabel="terminal error",
                title="Example 1: error vs CPU time")
    save_with_grids(figure, axes, directory, "example1_work_precision.png")


def plot_work_precision(axis, rows):
    """Terminal error vs CPU time of OCP solves, per method and n_s."""
    solved = [r for r in rows if r["status"] == "success"]
    for (method, n_s), group in sorted(series(solved,
                                              lambda r: (r["method"], int(r["n_s"]))).items()):
        group.sort(key=lambda r: float(r["cpu_s"]))
        axis.loglog([float(r["cpu_s"]) for r in group],
                    [max(float(r["terminal_error"]), 1e-16) for r in group],
                    "-o" if method == "fesd" else "--s", color=STAGE_COLORS.get(n_s),
                    label="%s n_s=%d (N_FE=%s)" % (method, n_s,
                                                   ",".join(r["n_fe"] for r in group)),
                    markersize=4)
    axis.set(xlabel="CPU time of the OCP solve [s]")
    axis.grid(True, which="both", alpha=0.3)
    axis.legend(fontsize=7)


def plot_ocp_accuracy(directory, rows):
    figure, axis = plt.subplots(figsize=(7, 5))
    plot_work_precision(axis, rows)
    axis.set(ylabel="terminal error vs a fine re-simulation",
             title="Manipulation showcase (N_ctrl = %s)" % (rows[0]["intervals"] if rows else "?"))
    save(figure, directory, "ocp_work_precision.png")


def plot_filippov(directory, order_rows, ocp_rows):
    figure, axes = plt.subplots(1, 2, figsize=(12, 5))
    if order_rows:
        plot_orders(axes[:1], order_rows, FILIPPOV_ASYMPTOTIC_FROM)
        axes[0].set(xlabel="h", ylabel="terminal error", title="Example (47): error vs step")
        axes[0].grid(True, which="both", alpha=0.3)
        axes[0].legend(fontsize=6)
    if ocp_rows:
        plot_work_precision(axes[1], ocp_rows)
        axes[1].set(ylabel="|x_int(T) - x_final| (fine re-simulation)",
                    title="OCP (61): terminal error vs CPU time (N_ctrl = 6)")
    save(figure, directory, "filippov_work_precision.png")


def plot_scaling(directory, rows):
    figure, axes = plt.subplots(1, 2, figsize=(12, 5))
    by_intervals = [r for r in rows if r["sweep"] == "intervals"]
    axes[0].plot([int(r["intervals"]) for r in by_intervals],
                 [float(r["cpu_s"]) for r in by_intervals], "-o", label="showcase, FESD")
    axes[0].set(xlabel="N_ctrl", ylabel="CPU time [s]", title="Solve time vs N_ctrl")
    for pruning, group in sorted(series([r for r in rows if r["sweep"] == "bodies"],
                                        lambda r: r["pruning"]).items()):
        axes[1].plot([int(r["bodies"]) for r in group], [float(r["cpu_s"]) for r in group],
                     "-o" if pruning == "on" else "--s", label="pruning " + pruning)
    axes[1].set(xlabel="bodies (lanes of pusher + puck)", ylabel="CPU time [s]",
                title="Solve time vs bodies")
    for axis in axes:
        axis.grid(True, alpha=0.3)
        axis.legend()
    save(figure, directory, "scaling.png")


FAMILY_COLORS = {"push": "tab:blue", "wall": "tab:orange", "beside": "tab:green",
                 "second": "tab:purple", "showcase": "tab:red", "cluttered": "tab:gray"}


def plot_sweep_accuracy(directory, rows):
    """Per planning-sweep scene, its accuracy ladder: verification error vs the wall time spent
    up to each rung (solves and verifications), one line per scene, coloured by family."""
    figure, axis = plt.subplots(figsize=(8, 5.5))
    labelled = set()
    for (name, seed), group in sorted(series([r for r in rows if int(r["rung"]) > 0],
                                             lambda r: (r["family"], int(r["seed"]))).items()):
        group = [r for r in group if r["status"] in ("success", "target_not_reached")]
        if not group:
            continue
        group.sort(key=lambda r: int(r["rung"]))
        axis.loglog([float(r["cumulative_s"]) for r in group],
                    [max(float(r["verification_error"]), 1e-16) for r in group], "-o",
                    color=FAMILY_COLORS.get(name, "black"), markersize=3, alpha=0.7,
                    label=None if name in labelled else name)
        labelled.add(name)
    axis.axhline(1e-2, color="black", linestyle=":", linewidth=1,
                 label="the node's default target_accuracy")
    axis.set(xlabel="wall time up to the rung (solves + verifications) [s]",
             ylabel="verification error (fine re-simulation)",
             title="Planning sweep: each scene's accuracy ladder (first point: default grid)")
    axis.grid(True, which="both", alpha=0.3)
    axis.legend(fontsize=7)
    save(figure, directory, "sweep_accuracy.png")


METHOD_STYLES = {"analytic": ("black", "-", "analytic"), "fesd": ("tab:blue", "--", "FESD"),
                 "standard": ("tab:red", ":", "standard time-stepping")}


def plot_sensitivity(directory, sweep_rows, order_rows):
    """Nurkanovic et al. 2024 Fig. 9 and beyond: V(x0) = (x(2) - 5/3)^2 and dV/dx0 for
    x' = 2 - sign(x) by FESD, standard time-stepping and in closed form; and the error of
    dx(T)/dx0 against the step for that system and the spiral (eq. 47), both methods."""
    figure, axes = plt.subplots(1, 3, figsize=(15, 4.5))
    for method, (color, style, label) in METHOD_STYLES.items():
        rows = sorted((r for r in sweep_rows if r["method"] == method), key=lambda r: float(r["x0"]))
        x0 = [float(r["x0"]) for r in rows]
        axes[0].plot(x0, [float(r["value"]) for r in rows], style, color=color, label=label)
        axes[1].plot(x0, [float(r["dvalue"]) for r in rows], style, color=color, label=label)
    axes[0].set(xlabel="x0", ylabel="V(x0) = (x(2) - 5/3)^2",
                title="x' = 2 - sign(x): the value (25 steps)")
    axes[1].set(xlabel="x0", ylabel="dV/dx0 (the simulation's sensitivity)",
                title="its derivative: FESD exact, time-stepping not")
    markers = {"two_minus_sign": "o", "spiral": "s"}
    for (system, method), rows in sorted(series(order_rows,
                                                lambda r: (r["system"], r["method"])).items()):
        rows = [r for r in rows if r["status"] == "success" and r["sensitivity_error"] != "nan"]
        color, style, label = METHOD_STYLES[method]
        axes[2].loglog([float(r["step"]) for r in rows],
                       [max(float(r["sensitivity_error"]), 1e-16) for r in rows], style,
                       marker=markers[system], color=color, label="%s, %s" % (label, system))
    steps = [float(r["step"]) for r in order_rows]
    if steps:
        reference = [3e0 * (h / max(steps)) ** 3 for h in sorted(steps)]
        axes[2].loglog(sorted(steps), reference, color="gray", linewidth=0.8, label="order 3")
    axes[2].set(xlabel="step h", ylabel="relative error of dx(T)/dx0",
                title="sensitivity error against the step (Radau IIA, n_s = 2)")
    save_with_grids(figure, axes, directory, "sensitivity.png")


def read_push_t(directory):
    """push_t_trajectory.csv (fesd_bench push-t --trajectory): its comment lines (the T's spheres,
    the pusher's radius, the target) and its rows."""
    path = os.path.join(directory, "push_t_trajectory.csv")
    if not os.path.exists(path):
        print("plot_benchmarks: no %s, its plot is skipped" % path)
        return None
    spheres, header, lines = [], {}, []
    with open(path) as f:
        for line in f:
            if line.startswith("# sphere,"):
                spheres.append([float(v) for v in line.split(",")[1:]])
            elif line.startswith("# "):
                key, *values = line[2:].strip().split(",")
                header[key] = values
            else:
                lines.append(line)
    return spheres, header, list(csv.DictReader(lines))


def plot_push_t(directory, spheres, header, rows):
    """The T at a few times (lighter earlier), its target outlined, the pusher's path and discs."""
    import math
    from matplotlib.patches import Circle

    figure, axis = plt.subplots(figsize=(6.5, 6.5))
    pusher_radius = float(header["pusher_radius"][0])
    target = [float(v) for v in header["target"]]

    def draw_t(x, y, yaw, **style):
        c, s = math.cos(yaw), math.sin(yaw)
        for ox, oy, r in spheres:
            axis.add_patch(Circle((x + c * ox - s * oy, y + s * ox + c * oy), r, **style))

    draw_t(*target, fill=False, edgecolor="tab:red", linestyle="--", linewidth=0.8)
    snapshots = 3
    for k in range(snapshots + 1):
        row = rows[round(k * (len(rows) - 1) / snapshots)]
        shade = 0.3 + 0.7 * k / snapshots
        draw_t(float(row["t_x"]), float(row["t_y"]), float(row["yaw"]),
               facecolor=(0.12, 0.47, 0.71, 0.3 * shade), edgecolor="none")
        axis.add_patch(Circle((float(row["pusher_x"]), float(row["pusher_y"])), pusher_radius,
                              facecolor=(1.0, 0.5, 0.05, shade), edgecolor="none"))
        axis.annotate("%.1f s" % float(row["t"]), (float(row["pusher_x"]), float(row["pusher_y"])),
                      fontsize=7, xytext=(4, 4), textcoords="offset points")
    axis.plot([float(r["pusher_x"]) for r in rows], [float(r["pusher_y"]) for r in rows],
              color="tab:orange", linewidth=0.8, label="pusher")
    axis.plot([float(r["t_x"]) for r in rows], [float(r["t_y"]) for r in rows],
              color="tab:blue", linewidth=0.8, label="T (centre of pressure)")
    axis.plot([], [], color="tab:red", linestyle="--", label="target pose")
    axis.set_aspect("equal")
    axis.autoscale_view()
    axis.set_xlabel("x")
    axis.set_ylabel("y")
    axis.set_title("Push-T (%s): the T pushed to its pose" % header["status"][0], fontsize=10)
    axis.grid(True, alpha=0.3)
    axis.legend(fontsize=7, loc="best")
    save(figure, directory, "push_t.png")


def main():
    directory = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "docs", "benchmarks")
    order_rows = read(directory, "order_pds.csv")
    if order_rows:
        plot_example1(directory, order_rows, read(directory, "siconos_example1.csv"))
    accuracy_rows = read(directory, "ocp_accuracy.csv")
    if accuracy_rows:
        plot_ocp_accuracy(directory, accuracy_rows)
    scaling_rows = read(directory, "scaling.csv")
    if scaling_rows:
        plot_scaling(directory, scaling_rows)
    filippov_orders = read(directory, "order_filippov.csv")
    filippov_ocp = read(directory, "ocp_filippov.csv")
    if filippov_orders or filippov_ocp:
        plot_filippov(directory, filippov_orders, filippov_ocp)
    sensitivity_sweep = read(directory, "sensitivity_sweep.csv")
    sensitivity_order = read(directory, "sensitivity_order.csv")
    if sensitivity_sweep or sensitivity_order:
        plot_sensitivity(directory, sensitivity_sweep, sensitivity_order)
    sweep_rows = read(directory, "sweep_accuracy.csv")
    if sweep_rows:
        plot_sweep_accuracy(directory, sweep_rows)
    push_t = read_push_t(directory)
    if push_t and push_t[2]:
        plot_push_t(directory, *push_t)
    return 0


if __name__ == "__main__":
    sys.exit(main())
