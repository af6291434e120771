#include "ipopt_session.h"

#include "ipopt_linear_solver.h"

#include <dlfcn.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <mutex>
#include <stdexcept>

#include <coin/IpIpoptData.hpp>
#include <coin/IpSolveStatistics.hpp>
#include <coin/IpTNLP.hpp>

#include "fesd_trajopt/solver/square_newton.h"

namespace fesd {

double steadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

namespace {

/// SCOTCH (MUMPS' ordering) runs multithreaded by default, and then its orderings, and with
/// them the rounding of every factorization, differ from run to run; with one thread they are
/// the same in every run. Set at load time, before any thread exists; a value from the
/// environment is kept.
const bool kScotchSingleThreaded = setenv("SCOTCH_PTHREAD_NUMBER", "1", 0) == 0;

/// SCOTCH draws from one random generator per process, which goes on from one ordering to the
/// next: the same NLP solved twice in a process got two orderings, and results differing in
/// the last bits. Reset before every solve (each solve analyses its KKT matrix anew), it gives
/// every solve the same ordering of the same matrix. Found at run time: MUMPS may have been
/// built without SCOTCH (then mumps_pivot_order 3 falls back to another ordering).
void resetScotchRandom() {
  using Reset = void (*)();
  static const Reset reset = reinterpret_cast<Reset>(dlsym(RTLD_DEFAULT, "SCOTCH_randomReset"));
  if (reset != nullptr) reset();
}

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
    selectRows();  // here, not in the constructor: a problem that throws is Ipopt's failure
    n = problem_.numVariables();
    m = static_cast<Index>(rows_.size());
    nnz_jac_g = static_cast<Index>(jacobian_entries_.size());
    nnz_h_lag = problem_.hessianPattern().nonzeros();
    index_style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index, Number* x_l, Number* x_u, Index, Number* g_l, Number* g_u) override {
    std::vector<double> lower(problem_.numConstraints()), upper(problem_.numConstraints());
    problem_.getBounds(x_l, x_u, lower.data(), upper.data());
    for (size_t r = 0; r < rows_.size(); ++r) {
      g_l[r] = lower[rows_[r]];
      g_u[r] = upper[rows_[r]];
    }
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
      for (Index r = 0; r < m; ++r) lambda[r] = point_.constraint_multipliers[rows_[r]];
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
      problem_.constraints(x, full_rows_.data());
      for (Index r = 0; r < m; ++r) g[r] = full_rows_[rows_[r]];
      return allFinite(g, m);
    });
  }

  bool eval_jac_g(Index, const Number* x, bool, Index, Index nele, Index* rows, Index* cols,
                  Number* values) override {
    if (values == nullptr) {
      const SparsityPattern& pattern = problem_.jacobianPattern();
      for (size_t e = 0; e < jacobian_entries_.size(); ++e) {
        rows[e] = row_index_[pattern.rows[jacobian_entries_[e]]];
        cols[e] = pattern.cols[jacobian_entries_[e]];
      }
      return true;
    }
    return timed([&] {
      problem_.jacobian(x, full_jacobian_.data());
      for (Index e = 0; e < nele; ++e) values[e] = full_jacobian_[jacobian_entries_[e]];
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
      for (size_t r = 0; r < rows_.size(); ++r) full_rows_[rows_[r]] = lambda[r];
      problem_.hessian(x, objective_factor, full_rows_.data(), values);
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
    point_.constraint_multipliers.assign(problem_.numConstraints(), 0.0);
    for (Index r = 0; r < m; ++r) point_.constraint_multipliers[rows_[r]] = lambda[r];
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

  /// The complementarity product rows of a polishing NLP (both bounds infinite: the active set
  /// is fixed by variable bounds) constrain nothing, but Ipopt would still give each a slack and
  /// a multiplier, two zero-diagonal rows and columns of the KKT matrix coupled to both sides of
  /// the pair. They are left out (multipliers 0). On the 44-pair scene (5280 pairs) the polishing
  /// KKT matrix went from 41680 to 31120 rows, MUMPS' delayed pivots from 27000 to ~7000, and
  /// its factorization from 1.3-2 s to 0.05-0.1 s. Only these rows: leaving out the relaxed NLPs'
  /// free equal-step rows as well changed the showcase's homotopy path (N = 20: 38 instead of
  /// 33 iterations; N = 50 and 60 ended in other local optima).
  void selectRows() {
    const int m = problem_.numConstraints();
    std::vector<double> x_lower(problem_.numVariables()), x_upper(problem_.numVariables());
    std::vector<double> lower(m), upper(m);
    problem_.getBounds(x_lower.data(), x_upper.data(), lower.data(), upper.data());
    rows_.clear();
    jacobian_entries_.clear();
    row_index_.assign(m, -1);
    std::vector<bool> product_row(m, false);
    if (const auto* mpcc = dynamic_cast<const RelaxedMpcc*>(&problem_)) {
      for (int row : mpcc->complementarityRows()) product_row[row] = true;
    }
    for (int r = 0; r < m; ++r) {
      if (!product_row[r] || lower[r] > -kUnbounded || upper[r] < kUnbounded) {
        row_index_[r] = static_cast<int>(rows_.size());
        rows_.push_back(r);
      }
    }
    const SparsityPattern& pattern = problem_.jacobianPattern();
    for (int e = 0; e < pattern.nonzeros(); ++e) {
      if (row_index_[pattern.rows[e]] >= 0) jacobian_entries_.push_back(e);
    }
    full_rows_.assign(m, 0.0);
    full_jacobian_.assign(pattern.nonzeros(), 0.0);
  }

  /// Ipopt's nlp_lower_bound_inf / nlp_upper_bound_inf (defaults).
  static constexpr double kUnbounded = 1e19;

  const NlpProblem& problem_;
  PrimalDualPoint& point_;
  std::vector<int> rows_;              ///< Ipopt's rows: the problem's rows that bound something
  std::vector<int> row_index_;         ///< per problem row: its Ipopt row, or -1
  std::vector<int> jacobian_entries_;  ///< the problem's Jacobian entries in Ipopt's rows
  std::vector<double> full_rows_, full_jacobian_;
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

/// MUMPS' options, where it is the linear solver.
void setMumpsOptions(Ipopt::OptionsList& options) {
  // MUMPS orders the KKT matrix by its graph alone (SCOTCH nested dissection), not through a
  // matching on the values of each NLP's first KKT matrix (Ipopt's default ICNTL(6) = 7, then
  // MUMPS' automatic compressed AMF ordering). On the 44-pair scene (26352 variables) the
  // default ordering varied with those values from 2.2e9 to 7.7e10 flops per factorization
  // (largest fronts 862-3697); SCOTCH's: 1.1e9 flops, fronts of at most ~500 (one element).
  options.SetIntegerValue("mumps_permuting_scaling", 0);
  options.SetIntegerValue("mumps_pivot_order", 3);
  // MUMPS allocates its workspace anew for every factorization, estimate x (1 + this / 100).
  // Above glibc's mmap threshold (32 MiB) that is fresh memory each time, and every page it
  // touches faults: with Ipopt's default 1000 a 16k-row KKT matrix (showcase, N = 120) took
  // 46 ms per factorization instead of 19 ms. With SCOTCH the factors exceeded the estimate by
  // at most 22 % (no "more memory" refactorization in any run measured).
  options.SetIntegerValue("mumps_mem_percent", 100);
}

void setBarrier(Ipopt::OptionsList& options, const BarrierStrategy& barrier) {
  options.SetStringValue("mu_strategy", barrier.mu_strategy);
  options.SetStringValue("adaptive_mu_globalization", barrier.globalization);
}

/// MUMPS keeps module-level state (its load balancing, dmumps_load): two solves in parallel
/// threads of one process crashed there, and so did one thread's solve while another ended its
/// MUMPS instance (destroying an Ipopt application ends the last one). Everything that runs
/// MUMPS takes this lock.
std::mutex& mumpsLock() {
  static std::mutex lock;
  return lock;
}

}  // namespace

IpoptSession::IpoptSession(const IpoptSettings& settings)
    : settings_(settings),
      uses_mumps_(settings.linear_solver == "mumps"),
      cold_start_options_({{"mu_init", "0.1"},
                           {"bound_push", "0.01"},
                           {"bound_frac", "0.01"},
                           {"slack_bound_push", "0.01"},
                           {"slack_bound_frac", "0.01"},
                           {"bound_mult_init_method", "constant"},
                           {"adaptive_mu_globalization", "obj-constr-filter"}}) {
  if (settings.linear_solver == kLdltSolver) registerLdltAsMa97();
  for (const auto& [name, value] : settings.extra_options) {
    if (cold_start_options_.count(name)) cold_start_options_[name] = value;
  }
  application_ = newApplication(0.0);
}

Ipopt::SmartPtr<Ipopt::IpoptApplication> IpoptSession::newApplication(double mu_max) {
  Ipopt::SmartPtr<Ipopt::IpoptApplication> application = IpoptApplicationFactory();
  Ipopt::OptionsList& options = *application->Options();
  options.SetStringValue("sb", "yes");
  options.SetIntegerValue("print_level", settings_.print_level);
  options.SetNumericValue("acceptable_tol", settings_.acceptable_tolerance);
  options.SetIntegerValue("max_iter", settings_.max_iterations);
  options.SetStringValue("hessian_approximation", "exact");
  // Complementarity products must be resolved far below Ipopt's default bound relaxation (1e-8).
  options.SetNumericValue("bound_relax_factor", 0.0);
  if (settings_.linear_solver == kLdltSolver) {
    // Ours answers under MA97's name; MA97's own scaling is not ours to offer.
    options.SetStringValue("linear_solver", "ma97");
    options.SetStringValue("ma97_scaling", "none");
  } else {
    options.SetStringValue("linear_solver", settings_.linear_solver);
  }
  if (uses_mumps_) setMumpsOptions(options);
  if (mu_max > 0.0) options.SetNumericValue("mu_max", mu_max);

  for (const auto& [name, value] : settings_.extra_options) {
    if (!setOption(options, name, value)) {
      throw std::invalid_argument("Ipopt option '" + name + "' does not accept '" + value + "'");
    }
  }
  if (application->Initialize() != Ipopt::Solve_Succeeded) {
    throw std::runtime_error("Ipopt could not be initialised (invalid option?)");
  }
  return application;
}

NlpOutcome IpoptSession::solve(const NlpProblem& problem, PrimalDualPoint& point,
                               const SolveSettings& solve_settings) {
  const bool near = !point.has_multipliers && point.near_solution &&
                    constraintViolation(problem, point.x) <= settings_.near_solution_violation;
  const bool bounded_barrier =
      !point.has_multipliers && !near && point.rows_added && settings_.added_rows_mu_max > 0.0;
  if (bounded_barrier && Ipopt::IsNull(bounded_barrier_application_)) {
    bounded_barrier_application_ = newApplication(settings_.added_rows_mu_max);
  }
  Ipopt::IpoptApplication& application =
      bounded_barrier ? *bounded_barrier_application_ : *application_;
  Ipopt::OptionsList& options = *application.Options();
  options.SetNumericValue("tol", solve_settings.tolerance);
  options.SetNumericValue("obj_scaling_factor", solve_settings.objective_scaling);
  options.SetNumericValue("mu_target", solve_settings.barrier_target);
  options.SetIntegerValue("max_iter", solve_settings.max_iterations > 0
                                          ? solve_settings.max_iterations
                                          : settings_.max_iterations);
  if (point.has_multipliers) {
    // Ipopt's warm-start initialiser reads only the warm_start_* pushes: the cold ones may stay.
    setBarrier(options,
               solve_settings.monotone_barrier ? BarrierStrategy{} : settings_.warm_start_barrier);
    options.SetStringValue("warm_start_init_point", "yes");
    options.SetNumericValue("mu_init", solve_settings.warm_start_mu);
    for (const char* name :
         {"warm_start_bound_push", "warm_start_bound_frac", "warm_start_slack_bound_push",
          "warm_start_slack_bound_frac", "warm_start_mult_bound_push"}) {
      options.SetNumericValue(name, solve_settings.warm_start_bound_push > 0.0
                                        ? solve_settings.warm_start_bound_push
                                        : settings_.warm_start_bound_push);
    }
  } else if (near) {
    setBarrier(options, settings_.near_solution_barrier);
    options.SetStringValue("warm_start_init_point", "no");
    options.SetNumericValue("mu_init", settings_.near_solution_mu);
    for (const char* name : {"bound_push", "bound_frac", "slack_bound_push", "slack_bound_frac"}) {
      options.SetNumericValue(name, settings_.near_solution_bound_push);
    }
    options.SetStringValue("bound_mult_init_method", "mu-based");
  } else {
    options.SetStringValue("mu_strategy", settings_.cold_start_mu_strategy);
    options.SetStringValue("warm_start_init_point", "no");
    for (const auto& [name, value] : cold_start_options_) setOption(options, name, value);
  }
  const auto start = std::chrono::steady_clock::now();
  Ipopt::SmartPtr<TnlpAdapter> adapter =
      new TnlpAdapter(problem, point, solve_settings.deadline_seconds, solve_settings.cancel);
  NlpOutcome outcome;
  std::unique_lock<std::mutex> mumps_turn;
  if (uses_mumps_) {
    mumps_turn = std::unique_lock<std::mutex>(mumpsLock());
    resetScotchRandom();
  }
  try {
    outcome.status = application.OptimizeTNLP(Ipopt::SmartPtr<Ipopt::TNLP>(GetRawPtr(adapter)));
  } catch (const std::exception&) {
    outcome.status = Ipopt::NonIpopt_Exception_Thrown;
  } catch (...) {
    outcome.status = Ipopt::Unrecoverable_Exception;
  }
  outcome.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  outcome.evaluation_seconds = adapter->evaluationSeconds();
  if (Ipopt::IsValid(application.Statistics())) {
    outcome.iterations = application.Statistics()->IterationCount();
    outcome.objective = application.Statistics()->FinalObjective();
  }
  return outcome;
}

IpoptSession::~IpoptSession() {
  if (!uses_mumps_) return;
  std::lock_guard<std::mutex> mumps_turn(mumpsLock());
  application_ = nullptr;  // ends the applications' MUMPS instances, if they made them
  bounded_barrier_application_ = nullptr;
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
