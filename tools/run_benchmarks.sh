#!/usr/bin/env bash
# Regenerates every benchmark table and plot in docs/benchmarks/ (CSV + PNG): installs what is
# missing, builds (Release), runs the sweeps, plots. Took 30 min on the 2-core machine (docs/benchmarks/README.md).
# tools/run_benchmarks.sh [order|siconos|ocp|scaling|filippov|sensitivity|sweep ...] (default: all)
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
install_dependencies
build_workspace
source_workspace
OUT="$REPO_DIR/docs/benchmarks"
mkdir -p "$OUT"
PARTS=("$@")
((${#PARTS[@]})) || PARTS=(order siconos ocp scaling filippov sensitivity sweep push-t)
for part in "${PARTS[@]}"; do
  echo "== $part"
  case "$part" in
    order)
      rosrun fesd_trajopt fesd_bench order-pds --repeat=3 >"$OUT/order_pds.csv"
      "$ROS_PYTHON" "$REPO_DIR/tools/fit_orders.py" "$OUT/order_pds.csv" >"$OUT/orders.csv"
      ;;
    siconos)
      if [ -x "$WS_DIR/devel/lib/fesd_trajopt/siconos_example1" ]; then
        rosrun fesd_trajopt siconos_example1 --repeat=3 >"$OUT/siconos_example1.csv"
      else
        echo "Siconos was not found at build time: the peer benchmark is skipped"
      fi
      ;;
    ocp) rosrun fesd_trajopt fesd_bench ocp-accuracy --budget=60 >"$OUT/ocp_accuracy.csv" ;;
    scaling) rosrun fesd_trajopt fesd_bench scaling --budget=60 >"$OUT/scaling.csv" ;;
    filippov)
      # Implicit Euler damps example (47)'s spiral on coarse grids: it gets finer ones too.
      rosrun fesd_trajopt fesd_bench order-filippov >"$OUT/order_filippov.csv"
      rosrun fesd_trajopt fesd_bench order-filippov --radau-stages=1 --gauss-stages= \
        --totals=256,512,1024 --elements=32 | tail -n +2 >>"$OUT/order_filippov.csv"
      "$ROS_PYTHON" "$REPO_DIR/tools/fit_orders.py" "$OUT/order_filippov.csv" \
        --from-total radau_iia:1=256 >"$OUT/orders_filippov.csv"
      rosrun fesd_trajopt fesd_bench ocp-filippov >"$OUT/ocp_filippov.csv"
      rosrun fesd_trajopt fesd_bench sign-ocp >"$OUT/sign_ocp.csv"
      ;;
    sensitivity)
      rosrun fesd_trajopt fesd_bench sensitivity --table=sweep >"$OUT/sensitivity_sweep.csv"
      rosrun fesd_trajopt fesd_bench sensitivity --table=order >"$OUT/sensitivity_order.csv"
      rosrun fesd_trajopt fesd_bench sensitivity --table=scenes >"$OUT/sensitivity_scenes.csv"
      ;;
    sweep)
      rosrun fesd_trajopt fesd_bench sweep-accuracy --scenes=8 >"$OUT/sweep_accuracy.csv"
      rosrun fesd_trajopt fesd_bench sweep-accuracy --families=cluttered --scenes=4 |
        tail -n +2 >>"$OUT/sweep_accuracy.csv"
      ;;
    push-t)
      OPENBLAS_NUM_THREADS=1 rosrun fesd_trajopt fesd_bench push-t --starts=16 --budget=40 \
        --trajectory="$OUT/push_t_trajectory.csv" --trajectory-seed=2 >"$OUT/push_t.csv"
      ;;
    *) echo "unknown part '$part' (order, siconos, ocp, scaling, filippov, sensitivity, sweep," \
      "push-t)" >&2
      exit 2 ;;
  esac
done
"$ROS_PYTHON" "$REPO_DIR/tools/plot_benchmarks.py" "$OUT"
