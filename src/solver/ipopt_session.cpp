#include "ipopt_session.h"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <mutex>
#include <stdexcept>

#include <coin/IpIpoptData.hpp>
#include <coin/IpSolveStatistics.hpp>
#include <coin/IpTNLP.hpp>

namespace fesd {

double steadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

namespace {

using Ipopt::Index;
using Ipopt::Number;

bool allFinite(const double* values, int count) {
  for (int i = 0; i < count; ++i) {
    if (!std::isfinite(values[i])) return false;
  }
  return true;
}

/// Ipopt's view of an NlpProblem: forwards every callback, times our evaluations, honours a
/// deadline and records the final primal-dual iterate.
class TnlpAdapter : public Ipopt::TNLP {
 public:
  TnlpAdapter(const NlpProblem& problem, PrimalDualPoint& point, double deadline,
              const std::atomic<bool>* cancel)
      : problem_(problem), point_(point), deadline_(deadline), cancel_(cancel) {}

  double evaluationSeconds() const { return evaluation_seconds_; }

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag,
                    IndexStyleEnum& index_style) override {
    n = problem_.numVariables();
    m = problem_.numConstraints();
    nnz_jac_g = problem_.jacobianPattern().nonzeros();
    nnz_h_lag = problem_.hessianPattern().nonzeros();
    index_style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index, Number* x_l, Number* x_u, Index, Number* g_l, Number* g_u) override {
    problem_.getBounds(x_l, x_u, g_l, g_u);
    return true;
  }

  bool get_starting_point(Index n, bool init_x, Number* x, bool init_z, Number* z_l, Number* z_u,
                          Index m, bool init_lambda, Number* lambda) override {
    if ((init_z || init_lambda) && !point_.has_multipliers) return false;
    if (init_x) std::copy(point_.x.begin(), point_.x.begin() + n, x);
    if (init_z) {
      std::copy(point_.bound_lower_multipliers.begin(), point_.bound_lower_multipliers.end(), z_l);
      std::copy(point_.bound_upper_multipliers.begin(), point_.bound_upper_multipliers.end(), z_u);
    }
    if (init_lambda) {
      std::copy(point_.constraint_multipliers.begin(), point_.constraint_multipliers.begin() + m,
                lambda);
    }
    return true;
  }

  bool eval_f(Index n, const Number* x, bool, Number& value) override {
    return timed([&] {
      value = problem_.objective(x);
      return std::isfinite(value);
    });
  }

  bool eval_grad_f(Index n, const Number* x, bool, Number* gradient) override {
    return timed([&] {
      problem_.objectiveGradient(x, gradient);
      return allFinite(gradient, n);
    });
  }

  bool eval_g(Index, const Number* x, bool, Index m, Number* g) override {
    return timed([&] {
      problem_.constraints(x, g);
      return allFinite(g, m);
    });
  }

  bool eval_jac_g(Index, const Number* x, bool, Index, Index nele, Index* rows, Index* cols,
                  Number* values) override {
    if (values == nullptr) {
      const SparsityPattern& pattern = problem_.jacobianPattern();
      std::copy(pattern.rows.begin(), pattern.rows.end(), rows);
      std::copy(pattern.cols.begin(), pattern.cols.end(), cols);
      return true;
    }
    return timed([&] {
      problem_.jacobian(x, values);
      return allFinite(values, nele);
    });
  }

  bool eval_h(Index, const Number* x, bool, Number objective_factor, Index, const Number* lambda,
              bool, Index nele, Index* rows, Index* cols, Number* values) override {
    if (values == nullptr) {
      const SparsityPattern& pattern = problem_.hessianPattern();
      std::copy(pattern.rows.begin(), pattern.rows.end(), rows);
      std::copy(pattern.cols.begin(), pattern.cols.end(), cols);
      return true;
    }
    return timed([&] {
      problem_.hessian(x, objective_factor, lambda, values);
      return allFinite(values, nele);
    });
  }

  bool intermediate_callback(Ipopt::AlgorithmMode, Index, Number, Number, Number, Number, Number,
                             Number, Number, Number, Index, const Ipopt::IpoptData*,
                             Ipopt::IpoptCalculatedQuantities*) override {
    if (cancel_ != nullptr && cancel_->load()) return false;
    return deadline_ <= 0.0 || steadySeconds() < deadline_;
  }

  void finalize_solution(Ipopt::SolverReturn, Index n, const Number* x, const Number* z_l,
                         const Number* z_u, Index m, const Number*, const Number* lambda, Number,
                         const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    point_.x.assign(x, x + n);
    point_.bound_lower_multipliers.assign(z_l, z_l + n);
    point_.bound_upper_multipliers.assign(z_u, z_u + n);
    point_.constraint_multipliers.assign(lambda, lambda + m);
    point_.has_multipliers = true;
  }

 private:
  /// Runs an evaluation, adds its wall time, and turns exceptions and non-finite values into an
  /// evaluation error that Ipopt handles by cutting its step.
  template <class Evaluation>
  bool timed(Evaluation evaluation) {
    const auto start = std::chrono::steady_clock::now();
    bool ok;
    try {
      ok = evaluation();
    } catch (const std::exception&) {
      ok = false;
    }
    evaluation_seconds_ +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return ok;
  }

  const NlpProblem& problem_;
  PrimalDualPoint& point_;
  double deadline_;
  const std::atomic<bool>* cancel_;
  double evaluation_seconds_ = 0.0;
};

/// Sets an option whose type is only known to Ipopt: as an integer, else a number, else text.
bool setOption(Ipopt::OptionsList& options, const std::string& name, const std::string& value) {
  char* end = nullptr;
  const long integer = std::strtol(value.c_str(), &end, 10);
  if (end != value.c_str() && *end == '\0' &&
      options.SetIntegerValue(name, static_cast<Ipopt::Index>(integer))) {
    return true;
  }
  const double number = std::strtod(value.c_str(), &end);
  if (end != value.c_str() && *end == '\0' && options.SetNumericValue(name, number)) return true;
  return options.SetStringValue(name, value);
}

}  // namespace

IpoptSession::IpoptSession(const IpoptSettings& settings)
    : settings_(settings), application_(IpoptApplicationFactory()) {
  Ipopt::OptionsList& options = *application_->Options();
  options.SetStringValue("sb", "yes");
  options.SetIntegerValue("print_level", settings.print_level);
  options.SetNumericValue("acceptable_tol", settings.acceptable_tolerance);
  options.SetIntegerValue("max_iter", settings.max_iterations);
  options.SetStringValue("linear_solver", settings.linear_solver);
  options.SetStringValue("hessian_approximation", "exact");
  // Complementarity products must be resolved far below Ipopt's default bound relaxation (1e-8).
  options.SetNumericValue("bound_relax_factor", 0.0);
  for (const auto& [name, value] : settings.extra_options) {
    if (!setOption(options, name, value)) {
      throw std::invalid_argument("Ipopt option '" + name + "' does not accept '" + value + "'");
    }
  }
  if (application_->Initialize() != Ipopt::Solve_Succeeded) {
    throw std::runtime_error("Ipopt could not be initialised (invalid option?)");
  }
}

NlpOutcome IpoptSession::solve(const NlpProblem& problem, PrimalDualPoint& point,
                               const SolveSettings& solve_settings) {
  Ipopt::OptionsList& options = *application_->Options();
  options.SetNumericValue("tol", solve_settings.tolerance);
  options.SetNumericValue("obj_scaling_factor", solve_settings.objective_scaling);
  if (point.has_multipliers) {
    options.SetStringValue("mu_strategy", settings_.mu_strategy);
    options.SetStringValue("warm_start_init_point", "yes");
    options.SetNumericValue("mu_init", solve_settings.warm_start_mu);
    for (const char* name :
         {"warm_start_bound_push", "warm_start_bound_frac", "warm_start_slack_bound_push",
          "warm_start_slack_bound_frac", "warm_start_mult_bound_push"}) {
      options.SetNumericValue(name, solve_settings.warm_start_bound_push > 0.0
                                        ? solve_settings.warm_start_bound_push
                                        : settings_.warm_start_bound_push);
    }
  } else {
    options.SetStringValue("mu_strategy", settings_.cold_start_mu_strategy);
    options.SetStringValue("warm_start_init_point", "no");
    options.SetNumericValue("mu_init", 0.1);
  }
  const auto start = std::chrono::steady_clock::now();
  Ipopt::SmartPtr<TnlpAdapter> adapter =
      new TnlpAdapter(problem, point, solve_settings.deadline_seconds, solve_settings.cancel);
  NlpOutcome outcome;
  // MUMPS keeps module-level state (its load balancing, dmumps_load): two solves in parallel
  // threads of one process crashed there. Solves in different threads take turns.
  static std::mutex mumps;
  std::lock_guard<std::mutex> one_solve_at_a_time(mumps);
  try {
    outcome.status = application_->OptimizeTNLP(Ipopt::SmartPtr<Ipopt::TNLP>(GetRawPtr(adapter)));
  } catch (const std::exception&) {
    outcome.status = Ipopt::NonIpopt_Exception_Thrown;
  } catch (...) {
    outcome.status = Ipopt::Unrecoverable_Exception;
  }
  outcome.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  outcome.evaluation_seconds = adapter->evaluationSeconds();
  if (Ipopt::IsValid(application_->Statistics())) {
    outcome.iterations = application_->Statistics()->IterationCount();
    outcome.objective = application_->Statistics()->FinalObjective();
  }
  return outcome;
}

bool IpoptSession::converged(Ipopt::ApplicationReturnStatus status) {
  return status == Ipopt::Solve_Succeeded || status == Ipopt::Solved_To_Acceptable_Level ||
         status == Ipopt::Feasible_Point_Found;
}

std::string IpoptSession::statusName(Ipopt::ApplicationReturnStatus status) {
  switch (status) {
    case Ipopt::Solve_Succeeded:
      return "solve_succeeded";
    case Ipopt::Solved_To_Acceptable_Level:
      return "solved_to_acceptable_level";
    case Ipopt::Infeasible_Problem_Detected:
      return "infeasible_problem_detected";
    case Ipopt::Search_Direction_Becomes_Too_Small:
      return "search_direction_too_small";
    case Ipopt::Diverging_Iterates:
      return "diverging_iterates";
    case Ipopt::User_Requested_Stop:
      return "stopped_at_deadline";
    case Ipopt::Feasible_Point_Found:
      return "feasible_point_found";
    case Ipopt::Maximum_Iterations_Exceeded:
      return "maximum_iterations_exceeded";
    case Ipopt::Restoration_Failed:
      return "restoration_failed";
    case Ipopt::Error_In_Step_Computation:
      return "error_in_step_computation";
    case Ipopt::Maximum_CpuTime_Exceeded:
      return "maximum_cpu_time_exceeded";
    case Ipopt::Not_Enough_Degrees_Of_Freedom:
      return "not_enough_degrees_of_freedom";
    case Ipopt::Invalid_Problem_Definition:
      return "invalid_problem_definition";
    case Ipopt::Invalid_Option:
      return "invalid_option";
    case Ipopt::Invalid_Number_Detected:
      return "invalid_number_detected";
    case Ipopt::Unrecoverable_Exception:
      return "unrecoverable_exception";
    case Ipopt::NonIpopt_Exception_Thrown:
      return "non_ipopt_exception";
    case Ipopt::Insufficient_Memory:
      return "insufficient_memory";
    case Ipopt::Internal_Error:
      return "internal_error";
  }
  return "unknown";
}

}  // namespace fesd
