#include "bench_args.h"

#include <sstream>
#include <stdexcept>

namespace fesd_bench {

Arguments::Arguments(int argc, char** argv, int first) {
  for (int i = first; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind("--", 0) != 0) throw std::invalid_argument("unexpected argument '" + arg + "'");
    const size_t eq = arg.find('=');
    const std::string name = arg.substr(2, eq == std::string::npos ? std::string::npos : eq - 2);
    values_[name] = eq == std::string::npos ? "true" : arg.substr(eq + 1);
  }
}

std::string Arguments::text(const std::string& name, const std::string& fallback) const {
  used_[name] = true;
  const auto it = values_.find(name);
  return it == values_.end() ? fallback : it->second;
}

double Arguments::number(const std::string& name, double fallback) const {
  const auto it = values_.find(name);
  used_[name] = true;
  return it == values_.end() ? fallback : std::stod(it->second);
}

int Arguments::integer(const std::string& name, int fallback) const {
  const auto it = values_.find(name);
  used_[name] = true;
  return it == values_.end() ? fallback : std::stoi(it->second);
}

bool Arguments::flag(const std::string& name, bool fallback) const {
  const std::string value = text(name, fallback ? "true" : "false");
  if (value == "true" || value == "1" || value == "on") return true;
  if (value == "false" || value == "0" || value == "off") return false;
  throw std::invalid_argument("--" + name + " takes true/false, got '" + value + "'");
}

std::vector<std::string> Arguments::texts(const std::string& name,
                                          const std::vector<std::string>& fallback) const {
  const auto it = values_.find(name);
  used_[name] = true;
  if (it == values_.end()) return fallback;
  std::vector<std::string> list;
  std::stringstream stream(it->second);
  std::string item;
  while (std::getline(stream, item, ',')) list.push_back(item);
  return list;
}

std::vector<int> Arguments::integers(const std::string& name,
                                     const std::vector<int>& fallback) const {
  std::vector<std::string> words;
  for (int value : fallback) words.push_back(std::to_string(value));
  std::vector<int> list;
  for (const std::string& word : texts(name, words)) list.push_back(std::stoi(word));
  return list;
}

void Arguments::rejectUnused() const {
  for (const auto& [name, value] : values_) {
    if (!used_.count(name)) throw std::invalid_argument("unknown option --" + name);
  }
}

fesd::StepEquilibration stepEquilibration(const Arguments& args) {
  const std::string form = args.text("equilibration", "indicator");
  if (form == "indicator") return fesd::StepEquilibration::kIndicator;
  if (form == "tanh") return fesd::StepEquilibration::kTanhIndicator;
  if (form == "none") return fesd::StepEquilibration::kNone;
  throw std::invalid_argument("--equilibration takes indicator, tanh or none");
}

bool startsFromPlan(const Arguments& args) {
  const std::string start = args.text("start", "plan");
  if (start != "plan" && start != "constant") {
    throw std::invalid_argument("--start takes plan or constant");
  }
  return start == "plan";
}

fesd::PdsStepEquilibration pdsStepEquilibration(const Arguments& args) {
  const std::string form = args.text("pds-equilibration", "polishing");
  if (form == "polishing") return fesd::PdsStepEquilibration::kPolishing;
  if (form == "big-m") return fesd::PdsStepEquilibration::kBigM;
  throw std::invalid_argument("--pds-equilibration takes polishing or big-m");
}

fesd::SimulationOptions steppingArguments(const Arguments& args, bool refine_by_default) {
  fesd::SimulationOptions options;
  options.active_set_steps = args.integer("active-set", 1) != 0;
  options.refine_elements = args.integer("refine-elements", refine_by_default ? 1 : 0) != 0;
  options.max_element_stretch = args.number("max-element-stretch", options.max_element_stretch);
  return options;
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t middle = values.size() / 2;
  return values.size() % 2 ? values[middle] : 0.5 * (values[middle - 1] + values[middle]);
}

void applyHomotopyArguments(const Arguments& args, fesd::HomotopyOptions& options) {
  options.sigma_initial = args.number("sigma0", options.sigma_initial);
  options.sigma_reduction = args.number("kappa", options.sigma_reduction);
  options.relaxed_tolerance_factor =
      args.number("relaxed-tolerance-factor", options.relaxed_tolerance_factor);
  options.max_steps = args.integer("max-steps", options.max_steps);
  options.polish_iterations = args.integer("polish-iterations", options.polish_iterations);
  options.barrier_factor = args.number("barrier-factor", options.barrier_factor);
  options.ipopt.tolerance = args.number("ipopt-tol", options.ipopt.tolerance);
  fesd::BarrierStrategy& warm = options.ipopt.warm_start_barrier;
  fesd::BarrierStrategy& near = options.ipopt.near_solution_barrier;
  warm.mu_strategy = args.text("mu-strategy", warm.mu_strategy);
  near.mu_strategy = args.text("near-mu-strategy", near.mu_strategy);
  warm.globalization = args.text("warm-mu-globalization", warm.globalization);
  near.globalization = args.text("near-mu-globalization", near.globalization);
  options.ipopt.cold_start_mu_strategy =
      args.text("cold-mu-strategy", options.ipopt.cold_start_mu_strategy);
  options.ipopt.print_level = args.integer("ipopt-print-level", options.ipopt.print_level);
  options.ipopt.linear_solver = args.text("linear-solver", options.ipopt.linear_solver);
  options.ipopt.near_solution_violation =
      args.number("near-solution-violation", options.ipopt.near_solution_violation);
  options.ipopt.added_rows_mu_max =
      args.number("added-rows-mu-max", options.ipopt.added_rows_mu_max);
  const std::string method = args.text("mpcc-method", fesd::methodName(options.method));
  if (!fesd::parseMethod(method, options.method)) {
    throw std::invalid_argument("--mpcc-method=homotopy|active_set");
  }
  for (const std::string& option : args.texts("ipopt", {})) {
    const size_t colon = option.find(':');
    if (colon == std::string::npos) throw std::invalid_argument("--ipopt takes name:value,...");
    options.ipopt.extra_options[option.substr(0, colon)] = option.substr(colon + 1);
  }
}

}  // namespace fesd_bench
