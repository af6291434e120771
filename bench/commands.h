#pragma once

#include "bench_args.h"

namespace fesd_bench {

/// Each command prints its results to stdout and returns the process exit code.
int orderPds(const Arguments& args);
int orderFilippov(const Arguments& args);
int ocpFilippov(const Arguments& args);
int signOcp(const Arguments& args);
int sensitivity(const Arguments& args);
int derivatives(const Arguments& args);
int ocpManipulation(const Arguments& args);
int ocpAccuracy(const Arguments& args);
int scaling(const Arguments& args);
int homotopyFailures(const Arguments& args);
int simulationSweep(const Arguments& args);
int replan(const Arguments& args);
int planningSweep(const Arguments& args);
int closedLoop(const Arguments& args);
int sweepAccuracy(const Arguments& args);
int kkt(const Arguments& args);
int kktSolvers(const Arguments& args);
int robotPush(const Arguments& args);
int robotPushes(const Arguments& args);
int mpccMethods(const Arguments& args);
int pushT(const Arguments& args);
int scaleSweep(const Arguments& args);

}  // namespace fesd_bench
