#pragma once

#include <map>
#include <string>
#include <vector>

#include "fesd_trajopt/discretization/discretization_options.h"
#include "fesd_trajopt/integrator/fesd_integrator.h"
#include "fesd_trajopt/solver/mpcc_solver.h"

namespace fesd_bench {

/// Command-line options of the form --name=value (or --flag for "true").
class Arguments {
 public:
  Arguments(int argc, char** argv, int first);
  std::string text(const std::string& name, const std::string& fallback) const;
  double number(const std::string& name, double fallback) const;
  int integer(const std::string& name, int fallback) const;
  bool flag(const std::string& name, bool fallback) const;
  /// A comma-separated list of integers, e.g. --stages=1,2,3.
  std::vector<int> integers(const std::string& name, const std::vector<int>& fallback) const;
  /// A comma-separated list of words, e.g. --methods=fesd,standard.
  std::vector<std::string> texts(const std::string& name,
                                 const std::vector<std::string>& fallback) const;
  /// Throws if an option was given that no accessor asked for (catches typos).
  void rejectUnused() const;

 private:
  std::map<std::string, std::string> values_;
  mutable std::map<std::string, bool> used_;
};

/// --equilibration=indicator|tanh|none: a Filippov system's step equilibration.
fesd::StepEquilibration stepEquilibration(const Arguments& args);

/// --start=plan|constant: whether a scene OCP starts from its push plan (as the node does) or from
/// every state at x0.
bool startsFromPlan(const Arguments& args);

/// --pds-equilibration=polishing|big-m: how a PDS discretisation imposes step equilibration.
fesd::PdsStepEquilibration pdsStepEquilibration(const Arguments& args);

/// Integrator options with --refine-elements=0|1, --max-element-stretch and --active-set=0|1
/// applied (SimulationOptions::refine_elements, active_set_steps). The order benches keep the
/// papers' fixed element counts unless asked, since a refined part would leave the h axis.
fesd::SimulationOptions steppingArguments(const Arguments& args, bool refine_by_default);

/// Homotopy and Ipopt settings from --sigma0, --kappa, --max-steps, --relaxed-tolerance-factor,
/// --ipopt-tol,
/// --mu-strategy, --cold-mu-strategy, --ipopt-print-level and --ipopt=name:value,name:value.
void applyHomotopyArguments(const Arguments& args, fesd::HomotopyOptions& options);

/// The median (of an even count, the mean of the middle two); 0 for none.
double median(std::vector<double> values);

}  // namespace fesd_bench
