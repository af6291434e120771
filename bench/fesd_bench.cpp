// fesd_bench: benchmark programs that print tables (CSV or key=value lines).
#include <cstring>
#include <exception>
#include <functional>
#include <iostream>
#include <map>
#include <string>

#include "commands.h"
#include "fesd_trajopt/solver/heap_policy.h"

namespace {

struct Command {
  std::function<int(const fesd_bench::Arguments&)> run;
  const char* summary;
};

const std::map<std::string, Command>& commands() {
  static const std::map<std::string, Command> table = {
      {"closed-loop",
       {fesd_bench::closedLoop,
        "Plans executed with feedback over the planning sweep's scenes: the first plan at the\n"
        "    node's defaults, its open-loop replay, replans every --every intervals from the\n"
        "    plant's state, warm from the plan before: the pushed body's distance from its target\n"
        "    open and closed loop, the replans' time over the first plan's, CSV.\n"
        "    --families=cluttered --first-seed=0 --scenes=12 --every=3 --budget=60 --horizon\n"
        "    --intervals --min-open-loop=0 (only scenes whose open loop misses by more)\n"
        "    --replans (a line per replan) and the homotopy/Ipopt options of ocp-manipulation"}},
      {"derivatives",
       {fesd_bench::derivatives,
        "Cost of one model evaluation (value + Jacobian + Hessian): analytic vs Eigen AutoDiff.\n"
        "    --repeat=200000"}},
      {"homotopy-failures",
       {fesd_bench::homotopyFailures,
        "Continue after a failed relaxed NLP or stop: status, failed NLPs, iterations, time and\n"
        "    error of circle/chain simulations and showcase OCPs with both settings, CSV.\n"
        "    --stages=1,2,3,4 --steps=5,10,20,40 --intervals=10,20,30"}},
      {"push-t",
       {fesd_bench::pushT,
        "Push-T (a T of 12 spheres that turns, one disc pusher, the benchmark's target pose)\n"
        "    from random starts through the node's default request: status, seconds, iterations,\n"
        "    position and yaw errors, CSV and a summary against the default scene; --trajectory\n"
        "    writes one start's plan (--trajectory-seed, by default the first).\n"
        "    --starts=16 --first-seed=0 --budget=60 --accuracy=1e-2 --trajectory=PATH\n"
        "    --trajectory-seed=N and the homotopy/Ipopt options of ocp-manipulation"}},
      {"kkt",
       {fesd_bench::kkt,
        "The showcase plus --rocks passive discs in reach: NLP sizes, densest Jacobian rows and\n"
        "    columns, KKT degrees, and one solve (iterations, Ipopt time per iteration).\n"
        "    --rocks=7 --intervals=40 --elements=3 --stages=2 --solve=true --history "
        "--dump=PREFIX\n"
        "    --budget=600 and the homotopy/Ipopt options of ocp-manipulation "
        "(--ipopt=name:value)"}},
      {"kkt-solvers",
       {fesd_bench::kktSolvers,
        "Our LDL^T against MUMPS: per scene the whole solve under each (status, iterations,\n"
        "    objective, wall time; our analyses, factorisations and solves counted and timed),\n"
        "    then the first --keep KKT matrices replayed through both (analysis, ms per\n"
        "    factorisation and per solve, fill, inertia agreement).\n"
        "    --scenes=default,ten_discs,all_pairs,panda --intervals=40 --keep=2 --repeats=3\n"
        "    --budget=600"}},
      {"ocp-manipulation",
       {fesd_bench::ocpManipulation,
        "The collaborative manipulation OCP (Pozharskiy et al. 2024 Sec. IV-B), key=value per "
        "run.\n"
        "    --intervals=30 --elements=3 --stages=2 --fesd=true --repeat=1 --step-bound=0.5\n"
        "    --start=plan|constant (first guess: the push plan, or every state at x0)\n"
        "    --guess-sigma=1e-2 --guess-early-polish=1e-2 --fixed-grid-until=1e-2 (constant)\n"
        "    --resim-stages=n_s+1 --resim-elements=2*elements\n"
        "    --pds-equilibration=polishing|big-m --big-m=1e9 (step equilibration)\n"
        "    --divergence (per interval: OCP vs fine re-simulation, fine vs twice finer)\n"
        "    --history (per relaxed NLP) --trajectory (per interval; switches)\n"
        "    homotopy: --sigma0 --kappa --max-steps --relaxed-tolerance-factor --barrier-factor\n"
        "    --polish-iterations=100\n"
        "    --ipopt-tol --mu-strategy --cold-mu-strategy --ipopt-print-level "
        "--ipopt=name:value,...\n"
        "    --near-mu-strategy --warm-mu-globalization --near-mu-globalization (Ipopt's barrier\n"
        "    in warm starts and starts next to a plan; monotone for both: the old path)\n"
        "    --near-solution-violation=1e-3 (< 0: a plan's point starts Ipopt cold)\n"
        "    --added-rows-mu-max=0.1 (a lazy round's cold start: the barrier's bound; 0: "
        "Ipopt's)"}},
      {"ocp-accuracy",
       {fesd_bench::ocpAccuracy,
        "Showcase: terminal accuracy (fine FESD re-simulation of the optimal controls) vs CPU\n"
        "    time, CSV. --intervals=30 --stages=1,2,3,4 --elements=1,2,3,4\n"
        "    --methods=fesd,standard --budget=120 (s per solve) --reference-stages=4\n"
        "    --reference-elements=8 --start=plan|constant (first guess)"}},
      {"scale-sweep",
       {fesd_bench::scaleSweep,
        "The default scene with every length times k (radii, positions, targets, bounds, speeds)\n"
        "    through the node's default request: status, iterations, seconds and the ratio to\n"
        "    k = 1's, first contact, objective / k^2 and the plan's deviation from k = 1's, CSV.\n"
        "    --factors=0.003,0.01,0.03,0.1,0.25,1,4,10,100 --budget=120 --accuracy=1e-2\n"
        "    --length-scaling=true --evaluation-threads=measured|one|two and the homotopy/Ipopt\n"
        "    options of ocp-manipulation"}},
      {"robot-push",
       {fesd_bench::robotPush,
        "A shipped robot push (examples/robot_scenes.h) after the showcase: status, wall time and\n"
        "    ratio, Ipopt iterations per homotopy step, pairs, NLP size, target distance, gaps,\n"
        "    contact and release times per pair. --robot=panda|planar_arm|ur3e|planar_iiwa\n"
        "    --pushed=puck|bar (the Panda's bar, turned on the table) --pairs=lazy|all\n"
        "    --intervals --horizon --elements --stages --budget=150 --margin --verify=true\n"
        "    --showcase=true --accuracy=0 (> 0: the accuracy ladder to it, as the node does)\n"
        "    --length-scaling=true --evaluation-threads=measured|one|two and the homotopy/Ipopt\n"
        "    options of ocp-manipulation"}},
      {"robot-pushes",
       {fesd_bench::robotPushes,
        "Every shipped robot push (Panda puck and bar, UR3e, planar iiwa, planar arm) through\n"
        "    the node's default request: status, seconds and ratio to the default scene's,\n"
        "    iterations, target and yaw errors, height change on the support, smallest gap, CSV.\n"
        "    --scenes=panda_puck,... --node-horizon (5 s, 40 intervals for all) --budget=120\n"
        "    --accuracy=1e-2 --all-pairs-up-to=32 --repeat=3 (seconds: the median of the runs\n"
        "    after the first, as the default scene's)\n"
        "    --length-scaling=true --evaluation-threads=measured|one|two and the homotopy/Ipopt\n"
        "    options of ocp-manipulation"}},
      {"mpcc-methods",
       {fesd_bench::mpccMethods,
        "The homotopy and the active-set method (LPECs, branch NLPs) on the node's default\n"
        "    request of the default scene, the planning families and the shipped robots (Panda\n"
        "    at 20 intervals, 4 s): status, seconds, iterations, relaxed and branch NLPs, LPECs,\n"
        "    objective, certificate; CSV and a summary per method. --families=... --scenes=12\n"
        "    --first-seed=0 --robots=planar_arm,panda --methods=homotopy,active_set\n"
        "    --budget=120 --accuracy=1e-2"}},
      {"planning-sweep",
       {fesd_bench::planningSweep,
        "Seeded random planning scenes (families: push, wall, beside, second, showcase,\n"
        "    cluttered; examples/planning_scenes.h) solved as the node solves them and\n"
        "    verified with every pair in reach: status, wall time, pairs in reach / modelled /\n"
        "    rounds, target distance, penetration; CSV and a summary against the showcase.\n"
        "    --families=push,wall,beside,second,showcase,cluttered --first-seed=0 --scenes=20\n"
        "    --pairs=lazy|all --margin=0.1 --guess-sigma=1e-2 (the homotopy's start from the\n"
        "    plan)\n"
        "    --elements=3 --stages=2 --budget=120 --showcase=true"}},
      {"sweep-accuracy",
       {fesd_bench::sweepAccuracy,
        "What accuracy costs over the planning sweep's scenes: each climbs the accuracy ladder\n"
        "    to its end; per rung n_s, N_FE, status, wall time (solve + verification) and\n"
        "    verification error, CSV. --families=push,wall,beside,second,showcase --first-seed=0\n"
        "    --scenes=3 --elements=3 --stages=2 --max-stages=4 --max-elements=4 --budget=120"}},
      {"replan",
       {fesd_bench::replan,
        "Replanning: the showcase's object target moved --steps times by --step along x, each\n"
        "    plan warm-started from the last, against a cold solve of the same task, CSV.\n"
        "    --intervals=40 --elements=3 --steps=10 --step=0.03 --repeat=3 (best of) "
        "--budget=120"}},
      {"scaling",
       {fesd_bench::scaling,
        "Solve time vs N_ctrl (showcase) and vs bodies (lanes of pusher + puck, pruning on\n"
        "    and off), CSV. --sweeps=intervals,bodies --intervals=10,20,30,40,60,80\n"
        "    --lanes=1,2,3,4,6,8 --lane-intervals=10 --elements=2 --stages=2 --budget=120"}},
      {"order-filippov",
       {fesd_bench::orderFilippov,
        "Example (47) (Nurkanovic et al. 2024): terminal error vs step for FESD and standard, "
        "Radau-IIA and\n"
        "    Gauss-Legendre, CSV. --radau-stages=1,2,3 --gauss-stages=1,2\n"
        "    --totals=16,24,32,48,64,96,128 --elements=2 (per step) --methods=fesd,standard\n"
        "    --kappa=0.01 (homotopy) --equilibration=indicator|tanh|none\n"
        "    --equilibration-relaxation=1e6 (r of |dh/h0 eta| <= r sigma)\n"
        "    --refine-elements=0 (1: refine stretched elements) --max-element-stretch=1.05\n"
        "    --active-set=1 (0: the homotopy for every step)"}},
      {"ocp-filippov",
       {fesd_bench::ocpFilippov,
        "OCP (61) (Nurkanovic et al. 2024), two sliding surfaces: terminal error of a fine "
        "re-simulation of\n"
        "    the optimal controls vs CPU time, CSV. --stages=1,2,3,4 --elements=1,...,7\n"
        "    --methods=fesd,standard --family=radau|gauss --equilibration=indicator|tanh|none\n"
        "    --budget=120 (s per solve) --reference-stages=4 --reference-elements=12\n"
        "    --print-steps (element lengths and switch indicators eta per run)"}},
      {"simulation-sweep",
       {fesd_bench::simulationSweep,
        "Seeded random push scenes (2-4 discs or spheres, 2-D and 3-D, walls; first contact\n"
        "    often within 1 % of a step's start or end) simulated on every grid: status, terminal\n"
        "    error against the closed form or a fine FESD run, outlier grids (error > 100x both\n"
        "    neighbours'), CSV and summary. --first-seed=0 --scenes=24 --stages=1,2,3,4\n"
        "    --steps=4,5,6,8,10,12,16,20,24,32,40 --elements=2 --refine-elements=1\n"
        "    --max-element-stretch=1.05 --reference-steps=161 --budget=60 --active-set=1"}},
      {"sign-ocp",
       {fesd_bench::signOcp,
        "OCP (56) (Nurkanovic et al. 2024): x0 found from forward-simulation guesses, FESD vs "
        "standard, with a\n"
        "    homotopy or one relaxed NLP at a fixed sigma, or by OcpSolver from constant guesses,\n"
        "    CSV. --methods=fesd,standard --strategies=homotopy,fixed,ocp-solver\n"
        "    --fixed-sigma=1e-15 --guesses=-2.5,-2,...,2"}},
      {"sensitivity",
       {fesd_bench::sensitivity,
        "Sensitivities of simulations (Nurkanovic et al. 2024, Fig. 9), CSV: --table=sweep: "
        "x(T), V(x0)\n"
        "    and their derivatives for x' = 2 - sign(x) over x0 in [-2, 1], FESD, standard, "
        "analytic;\n"
        "    --table=order: dx(T)/dx0's error vs steps (sign, spiral); --table=scenes: random "
        "push scenes,\n"
        "    defined or not, against central differences, wall-time ratio with/without.\n"
        "    --steps=25 --points=121 --grids=4,8,...,256 --first-seed=0 --scenes=24 --repeat=5"}},
      {"order-pds",
       {fesd_bench::orderPds,
        "Example 1 (Pozharskiy et al. 2024): terminal error vs step for FESD and standard, "
        "Radau-IIA.\n"
        "    --stages=1,2,3,4 --totals=10,20,40,80,140,200,400 --elements=2 (per step)\n"
        "    --methods=fesd,standard --repeat=1 (timing: best of N) --profile (iterations per\n"
        "    homotopy level) --sigma0=1 --kappa=0.01 (homotopy) "
        "--pds-equilibration=polishing|big-m --big-m=1e9\n"
        "    --comp-tol=1e-9 --cross=sums|pairs (cross-complementarity form) --polish=true\n"
        "    --refine-elements=0 (1: refine stretched elements) --max-element-stretch=1.05\n"
        "    --active-set=1 (0: the homotopy for every step)"}},
  };
  return table;
}

void usage() {
  std::cout << "usage: fesd_bench <command> [--option=value ...]\n\ncommands:\n";
  for (const auto& [name, command] : commands()) {
    std::cout << "  " << name << "\n    " << command.summary << "\n";
  }
}

}  // namespace

int main(int argc, char** argv) {
  fesd::keepLargeAllocationsInTheHeap();
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "help")) {
    usage();
    return argc < 2 ? 2 : 0;
  }
  const auto it = commands().find(argv[1]);
  if (it == commands().end()) {
    std::cerr << "unknown command '" << argv[1] << "'\n";
    usage();
    return 2;
  }
  try {
    return it->second.run(fesd_bench::Arguments(argc, argv, 2));
  } catch (const std::exception& error) {
    std::cerr << "fesd_bench " << argv[1] << ": " << error.what() << "\n";
    return 2;
  }
}
