#include "fesd_trajopt/nlp/nlp_assembly.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <thread>

namespace fesd {

int SlotMap::slot(int row, int col) {
  const long long key = (static_cast<long long>(row) << 32) | static_cast<unsigned int>(col);
  const auto inserted = index_.emplace(key, pattern_.nonzeros());
  if (inserted.second) pattern_.add(row, col);
  return inserted.first->second;
}

namespace {
/// A free side counts as zero (the pair as biactive) below this fraction of the largest free
/// side: a failed polishing solve leaves such a side at its bound up to Ipopt's tolerance.
constexpr double kBiactiveFraction = 1e-7;

/// Hessian slots live in the lower triangle.
int lowerSlot(SlotMap& slots, int a, int b) {
  return slots.slot(std::max(a, b), std::min(a, b));
}
}  // namespace

void NlpAssembly::checkNotFinalized() const {
  if (finalized_) throw std::logic_error("NlpAssembly: structure is fixed after finalize()");
}

void NlpAssembly::checkFinalized() const {
  if (!finalized_) throw std::logic_error("NlpAssembly: finalize() before evaluating");
}

int NlpAssembly::addVariables(int count, double lower, double upper, double initial) {
  checkNotFinalized();
  const int first = numVariables();
  x_lower_.insert(x_lower_.end(), count, lower);
  x_upper_.insert(x_upper_.end(), count, upper);
  initial_.insert(initial_.end(), count, initial);
  return first;
}

int NlpAssembly::addRows(int count, double lower, double upper) {
  checkNotFinalized();
  const int first = numConstraints();
  g_lower_.insert(g_lower_.end(), count, lower);
  g_upper_.insert(g_upper_.end(), count, upper);
  return first;
}

int NlpAssembly::addRelaxedRows(int count, double scale) {
  const int first = addRows(count, -scale * sigma_, scale * sigma_);
  for (int r = 0; r < count; ++r) relaxed_rows_.push_back({first + r, scale});
  return first;
}

void NlpAssembly::addLinear(int row, int variable, double coefficient) {
  checkNotFinalized();
  linear_.push_back({row, variable, coefficient});
}

void NlpAssembly::addLinear(int row, const LinearExpression& expression) {
  for (const LinearTerm& term : expression) addLinear(row, term.variable, term.coefficient);
}

int NlpAssembly::addComplementarity(const LinearExpression& left, const LinearExpression& right,
                                    double left_weight, double right_weight) {
  const int row = addRows(1, -kInfinity, sigma_);
  complementarities_.push_back({row, left, right, left_weight, right_weight, {}, {}, {}});
  complementarity_rows_.push_back(row);
  return row;
}

void NlpAssembly::addFunctionTerm(std::shared_ptr<const SmoothFunction> function,
                                  std::vector<int> inputs, int scale_variable,
                                  std::vector<Target> targets) {
  checkNotFinalized();
  if (static_cast<int>(inputs.size()) != function->inputSize()) {
    throw std::invalid_argument("NlpAssembly: function term input size mismatch");
  }
  for (const Target& target : targets) {
    if (target.row == kObjective && function->outputSize() != 1) {
      throw std::invalid_argument("NlpAssembly: an objective term must be scalar");
    }
  }
  terms_.push_back(
      {std::move(function), std::move(inputs), scale_variable, std::move(targets), {}, {}, {}, {}});
}

void NlpAssembly::finalize() {
  checkNotFinalized();
  for (LinearEntry& entry : linear_) entry.slot = jacobian_slots_.slot(entry.row, entry.variable);
  for (Complementarity& comp : complementarities_) {
    for (const LinearTerm& t : comp.left) {
      comp.left_slots.push_back(jacobian_slots_.slot(comp.row, t.variable));
    }
    for (const LinearTerm& t : comp.right) {
      comp.right_slots.push_back(jacobian_slots_.slot(comp.row, t.variable));
    }
    for (const LinearTerm& l : comp.left) {
      for (const LinearTerm& r : comp.right) {
        comp.pair_slots.push_back(lowerSlot(hessian_slots_, l.variable, r.variable));
      }
    }
  }
  size_t inputs = 0, spans = 0, span = 0;  // every term's spans one after another, the largest
  for (FunctionTerm& term : terms_) {
    const SmoothFunction& f = *term.function;
    for (const Target& target : term.targets) {
      if (target.row != kObjective &&
          (target.row < 0 || target.row + f.outputSize() > numConstraints())) {
        throw std::invalid_argument("NlpAssembly: a function term's rows lie outside the NLP's");
      }
    }
    const SparsityPattern& jac = f.jacobianPattern();
    for (const Target& target : term.targets) {
      if (target.row == kObjective) continue;
      for (int e = 0; e < jac.nonzeros(); ++e) {
        term.jacobian_slots.push_back(
            jacobian_slots_.slot(target.row + jac.rows[e], term.inputs[jac.cols[e]]));
      }
      if (term.scale_variable >= 0) {
        for (int r = 0; r < f.outputSize(); ++r) {
          term.scale_jacobian_slots.push_back(
              jacobian_slots_.slot(target.row + r, term.scale_variable));
        }
      }
    }
    const SparsityPattern& hess = f.hessianPattern();
    for (int e = 0; e < hess.nonzeros(); ++e) {
      term.hessian_slots.push_back(
          lowerSlot(hessian_slots_, term.inputs[hess.rows[e]], term.inputs[hess.cols[e]]));
    }
    if (term.scale_variable >= 0) {
      term.scale_hessian_slots.assign(f.inputSize(), -1);
      for (int e = 0; e < jac.nonzeros(); ++e) {
        int& slot = term.scale_hessian_slots[jac.cols[e]];
        if (slot < 0) {
          slot = lowerSlot(hessian_slots_, term.scale_variable, term.inputs[jac.cols[e]]);
        }
      }
    }
    inputs = std::max(inputs, static_cast<size_t>(f.inputSize()));
    term.span = spans;
    spans += TermSpan::size(f);
    span = std::max(span, TermSpan::size(f));
  }
  scratch_inputs_.resize(inputs);
  scratch_span_.resize(span);
  finalized_ = true;
}

void NlpAssembly::setVariableBounds(int variable, double lower, double upper) {
  x_lower_.at(variable) = lower;
  x_upper_.at(variable) = upper;
}

void NlpAssembly::setRowBounds(int row, double lower, double upper) {
  g_lower_.at(row) = lower;
  g_upper_.at(row) = upper;
}

void NlpAssembly::getBounds(double* x_lower, double* x_upper, double* g_lower,
                            double* g_upper) const {
  std::copy(x_lower_.begin(), x_lower_.end(), x_lower);
  std::copy(x_upper_.begin(), x_upper_.end(), x_upper);
  std::copy(g_lower_.begin(), g_lower_.end(), g_lower);
  std::copy(g_upper_.begin(), g_upper_.end(), g_upper);
}

namespace {
/// Gathers a function term's argument vector from the NLP variables.
const double* gather(const std::vector<int>& inputs, const double* x, std::vector<double>& z) {
  for (size_t i = 0; i < inputs.size(); ++i) z[i] = x[inputs[i]];
  return z.data();
}
}  // namespace

double NlpAssembly::objective(const double* x) const {
  checkFinalized();
  double value = 0.0;
  for (const FunctionTerm& term : terms_) {
    for (const Target& target : term.targets) {
      if (target.row != kObjective) continue;
      const TermSpan span(*term.function, scratch_span_.data());
      term.function->evaluate(gather(term.inputs, x, scratch_inputs_), span.values);
      const double scale = term.scale_variable >= 0 ? x[term.scale_variable] : 1.0;
      value += coefficient(target) * scale * span.values[0];
    }
  }
  return value;
}

void NlpAssembly::objectiveGradient(const double* x, double* gradient) const {
  checkFinalized();
  std::fill(gradient, gradient + numVariables(), 0.0);
  for (const FunctionTerm& term : terms_) {
    for (const Target& target : term.targets) {
      if (target.row != kObjective) continue;
      const double* z = gather(term.inputs, x, scratch_inputs_);
      const SparsityPattern& jac = term.function->jacobianPattern();
      const TermSpan span(*term.function, scratch_span_.data());
      term.function->evaluateJacobian(z, span.jacobian);
      const double scale = term.scale_variable >= 0 ? x[term.scale_variable] : 1.0;
      for (int e = 0; e < jac.nonzeros(); ++e) {
        gradient[term.inputs[jac.cols[e]]] += coefficient(target) * scale * span.jacobian[e];
      }
      if (term.scale_variable >= 0) {
        term.function->evaluate(z, span.values);
        gradient[term.scale_variable] += coefficient(target) * span.values[0];
      }
    }
  }
}

void NlpAssembly::forEachTermOnOneThread(const double* x, const TermEvaluation& evaluate,
                                         const TermAddition& add) const {
  for (const FunctionTerm& term : terms_) {
    TermSpan span(*term.function, scratch_span_.data());
    evaluate(term, *term.function, gather(term.inputs, x, scratch_inputs_), span);
    add(term, span);
  }
}

void NlpAssembly::setEvaluationThreads(Threads threads) {
  for (PassThreads& pass : pass_threads_) pass = PassThreads{threads, 0};
}

void NlpAssembly::forEachTerm(Pass pass, const double* x, const TermEvaluation& evaluate,
                              const TermAddition& add) const {
  PassThreads& threads = pass_threads_[static_cast<int>(pass)];
  if (threads.mode == Threads::kTwo) return forEachTermOnTwoThreads(x, evaluate, add);
  if (threads.mode == Threads::kOne) return forEachTermOnOneThread(x, evaluate, add);
  // On one thread until kSlowEvaluations in a row take kTwoThreadSeconds: below that the
  // hand-over and every term's span cost more than the second core gives (measured: a scene of
  // discs' 0.06 ms evaluations took 0.2 ms on two). Not from the first: at a guess without
  // forces a pair's curvature terms are skipped; nor from one alone: the machine can slow one.
  const auto start = std::chrono::steady_clock::now();
  forEachTermOnOneThread(x, evaluate, add);
  const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
  threads.slow = took.count() >= kTwoThreadSeconds ? threads.slow + 1 : 0;
  if (threads.slow == kSlowEvaluations && std::thread::hardware_concurrency() >= 2) {
    threads.mode = Threads::kTwo;
  }
}

bool NlpAssembly::startHelper() const {
  // Built whole before it is kept: a copy or the thread that fails leaves one thread in charge.
  try {
    ThreadCopies copies;
    std::vector<std::shared_ptr<const SmoothFunction>> functions;
    for (const FunctionTerm& term : terms_) functions.push_back(copies.function(term.function));
    const int chunks = (static_cast<int>(terms_.size()) + kTermsPerChunk - 1) / kTermsPerChunk;
    auto done = std::make_unique<std::atomic<bool>[]>(chunks);
    auto helper = std::make_unique<HelperThread>();
    helper_inputs_.resize(scratch_inputs_.size());
    term_spans_.resize(terms_.back().span + TermSpan::size(*terms_.back().function));
    helper_functions_ = std::move(functions);
    chunk_done_ = std::move(done);
    helper_ = std::move(helper);
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

void NlpAssembly::forEachTermOnTwoThreads(const double* x, const TermEvaluation& evaluate,
                                          const TermAddition& add) const {
  if (terms_.empty() || (!helper_ && !startHelper())) {
    for (PassThreads& pass : pass_threads_) pass.mode = Threads::kOne;
    return forEachTermOnOneThread(x, evaluate, add);
  }
  const int count = static_cast<int>(terms_.size());
  const int chunks = (count + kTermsPerChunk - 1) / kTermsPerChunk;
  const auto lastOf = [&](int chunk) { return std::min(count, (chunk + 1) * kTermsPerChunk); };
  for (int c = 0; c < chunks; ++c) chunk_done_[c].store(false, std::memory_order_relaxed);
  // A term's span has the original's layout on either thread (a copy's patterns are its).
  const auto span = [&](const FunctionTerm& term) {
    return TermSpan(*term.function, term_spans_.data() + term.span);
  };
  std::atomic<int> next{0};
  // A failure on either thread ends the claims; the caller stops waiting for the helper's.
  std::atomic<bool> failed{false};
  int added = 0;  // chunks added, in order (by this thread only)
  const auto addDone = [&](bool wait) {
    for (; added < chunks; ++added) {
      while (!chunk_done_[added].load(std::memory_order_acquire)) {
        if (!wait || failed.load()) return;
        std::this_thread::yield();
      }
      for (int t = added * kTermsPerChunk; t < lastOf(added); ++t) add(terms_[t], span(terms_[t]));
    }
  };
  // Each thread evaluates the chunks it claims; this one also adds the evaluated chunks in the
  // terms' order as they are done, while the data is fresh. HelperThread::runBeside rethrows
  // what a function threw, on either thread.
  helper_->runBeside([&](int thread) {
    std::vector<double>& inputs = thread == 0 ? scratch_inputs_ : helper_inputs_;
    try {
      for (int chunk; !failed.load() && (chunk = next.fetch_add(1)) < chunks;) {
        for (int t = chunk * kTermsPerChunk; t < lastOf(chunk); ++t) {
          const FunctionTerm& term = terms_[t];
          TermSpan evaluated = span(term);
          evaluate(term, thread == 0 ? *term.function : *helper_functions_[t],
                   gather(term.inputs, x, inputs), evaluated);
        }
        chunk_done_[chunk].store(true, std::memory_order_release);
        if (thread == 0) addDone(false);
      }
    } catch (...) {
      failed = true;
      throw;
    }
    if (thread == 0) addDone(true);
  });
}

void NlpAssembly::constraints(const double* x, double* g) const {
  checkFinalized();
  std::fill(g, g + numConstraints(), 0.0);
  for (const LinearEntry& entry : linear_) g[entry.row] += entry.coefficient * x[entry.variable];
  for (const Complementarity& comp : complementarities_) {
    g[comp.row] += linearValue(comp.left, x) * linearValue(comp.right, x);
  }
  const auto rowTargets = [](const FunctionTerm& term) {
    return std::any_of(term.targets.begin(), term.targets.end(),
                       [](const Target& target) { return target.row != kObjective; });
  };
  forEachTerm(
      Pass::kValues, x,
      [&](const FunctionTerm& term, const SmoothFunction& f, const double* z, TermSpan& span) {
        if (rowTargets(term)) f.evaluate(z, span.values);
      },
      [&](const FunctionTerm& term, const TermSpan& span) {
        const int outputs = term.function->outputSize();
        const double scale = term.scale_variable >= 0 ? x[term.scale_variable] : 1.0;
        for (const Target& target : term.targets) {
          if (target.row == kObjective) continue;
          for (int r = 0; r < outputs; ++r) {
            g[target.row + r] += coefficient(target) * scale * span.values[r];
          }
        }
      });
}

void NlpAssembly::jacobian(const double* x, double* values) const {
  checkFinalized();
  std::fill(values, values + jacobian_slots_.pattern().nonzeros(), 0.0);
  for (const LinearEntry& entry : linear_) values[entry.slot] += entry.coefficient;
  for (const Complementarity& comp : complementarities_) {
    const double left = linearValue(comp.left, x), right = linearValue(comp.right, x);
    for (size_t i = 0; i < comp.left.size(); ++i) {
      values[comp.left_slots[i]] += comp.left[i].coefficient * right;
    }
    for (size_t i = 0; i < comp.right.size(); ++i) {
      values[comp.right_slots[i]] += comp.right[i].coefficient * left;
    }
  }
  const auto hasRows = [](const FunctionTerm& term) {
    return !term.jacobian_slots.empty() || !term.scale_jacobian_slots.empty();
  };
  forEachTerm(
      Pass::kJacobian, x,
      [&](const FunctionTerm& term, const SmoothFunction& f, const double* z, TermSpan& span) {
        if (!hasRows(term)) return;
        f.evaluateJacobian(z, span.jacobian);
        if (term.scale_variable >= 0) f.evaluate(z, span.values);
      },
      [&](const FunctionTerm& term, const TermSpan& span) {
        if (!hasRows(term)) return;
        const SmoothFunction& f = *term.function;
        const int nnz = f.jacobianPattern().nonzeros(), outputs = f.outputSize();
        const bool scaled = term.scale_variable >= 0;
        const double scale = scaled ? x[term.scale_variable] : 1.0;
        int target_index = 0;
        for (const Target& target : term.targets) {
          if (target.row == kObjective) continue;
          const int* slots = term.jacobian_slots.data() + target_index * nnz;
          for (int e = 0; e < nnz; ++e) {
            values[slots[e]] += coefficient(target) * scale * span.jacobian[e];
          }
          if (scaled) {
            const int* scale_slots = term.scale_jacobian_slots.data() + target_index * outputs;
            for (int r = 0; r < outputs; ++r) {
              values[scale_slots[r]] += coefficient(target) * span.values[r];
            }
          }
          ++target_index;
        }
      });
}

void NlpAssembly::termWeights(const FunctionTerm& term, double objective_factor,
                              const double* multipliers, double* weights) const {
  const int outputs = term.function->outputSize();
  std::fill(weights, weights + outputs, 0.0);
  for (const Target& target : term.targets) {
    if (target.row == kObjective) {
      weights[0] += coefficient(target) * objective_factor;
    } else {
      for (int r = 0; r < outputs; ++r) {
        weights[r] += coefficient(target) * multipliers[target.row + r];
      }
    }
  }
}

void NlpAssembly::hessian(const double* x, double objective_factor, const double* multipliers,
                          double* values) const {
  checkFinalized();
  std::fill(values, values + hessian_slots_.pattern().nonzeros(), 0.0);
  for (const Complementarity& comp : complementarities_) {
    const double multiplier = multipliers[comp.row];
    int k = 0;
    for (const LinearTerm& l : comp.left) {
      for (const LinearTerm& r : comp.right) {
        // A variable on both sides contributes d^2(x*x)/dx^2 = 2 on the diagonal.
        const double factor = l.variable == r.variable ? 2.0 : 1.0;
        values[comp.pair_slots[k++]] += factor * multiplier * l.coefficient * r.coefficient;
      }
    }
  }
  forEachTerm(
      Pass::kHessian, x,
      [&](const FunctionTerm& term, const SmoothFunction& f, const double* z, TermSpan& span) {
        termWeights(term, objective_factor, multipliers, span.weights);
        if (f.hessianPattern().nonzeros() > 0) f.evaluateHessian(z, span.weights, span.hessian);
        if (term.scale_variable >= 0) f.evaluateJacobian(z, span.jacobian);
      },
      [&](const FunctionTerm& term, const TermSpan& span) {
        const SmoothFunction& f = *term.function;
        const bool scaled = term.scale_variable >= 0;
        const double scale = scaled ? x[term.scale_variable] : 1.0;
        const int hess_nnz = f.hessianPattern().nonzeros();
        for (int e = 0; e < hess_nnz; ++e) values[term.hessian_slots[e]] += scale * span.hessian[e];
        if (scaled) {
          // d^2/(dh dz) of h * w^T F(z) is J(z)^T w.
          const SparsityPattern& jac = f.jacobianPattern();
          for (int e = 0; e < jac.nonzeros(); ++e) {
            values[term.scale_hessian_slots[jac.cols[e]]] +=
                span.weights[jac.rows[e]] * span.jacobian[e];
          }
        }
      });
}

void NlpAssembly::setRelaxation(double sigma) {
  sigma_ = sigma;
  for (int row : complementarity_rows_) g_upper_[row] = sigma;
  for (const auto& [row, scale] : relaxed_rows_) setRowBounds(row, -scale * sigma, scale * sigma);
}

NlpAssembly::ActiveSetChoice NlpAssembly::chooseActiveSet(const double* x) const {
  const int pairs = static_cast<int>(complementarities_.size());
  ActiveSetChoice choice;
  choice.left_is_zero.resize(pairs);
  choice.ambiguity.resize(pairs);
  // A side with a fixed nonzero term (data, e.g. c or lambda at a step's start point) cannot
  // vanish, so the other side must, however small this side is at x.
  const auto canVanish = [this](const std::vector<LinearTerm>& side) {
    for (const LinearTerm& t : side) {
      if (fixed(t.variable) && !fixedNearZero(t.variable)) return false;
    }
    return true;
  };
  // Sides a fixed active set may leave free of their product: nonnegative free variables only.
  const auto freeSide = [this](const std::vector<LinearTerm>& side) {
    for (const LinearTerm& t : side) {
      if (x_lower_[t.variable] == x_upper_[t.variable] || x_lower_[t.variable] != 0.0 ||
          t.coefficient <= 0.0) {
        return false;
      }
    }
    return true;
  };
  choice.biactive.assign(pairs, false);
  for (int p = 0; p < pairs; ++p) {
    const Complementarity& comp = complementarities_[p];
    const bool left_can_vanish = canVanish(comp.left), right_can_vanish = canVanish(comp.right);
    if (!left_can_vanish && !right_can_vanish) {
      choice.valid = false;
      return choice;
    }
    const double left = comp.left_weight * linearValue(comp.left, x);
    const double right = comp.right_weight * linearValue(comp.right, x);
    // Both sides far below the size sqrt(left_weight right_weight sigma) that each side of a
    // product at the relaxation's bound would have: the pair is biactive, not complementary.
    const double biactive_size =
        biactive_fraction_ * std::sqrt(comp.left_weight * comp.right_weight * biactive_sigma_);
    if (biactive_size > 0.0 && std::max(left, right) <= biactive_size && freeSide(comp.left) &&
        freeSide(comp.right)) {
      choice.biactive[p] = true;
      choice.left_is_zero[p] = false;  // one reading, so that active sets compare equal
      choice.ambiguity[p] = 0.0;
      continue;
    }
    choice.left_is_zero[p] = left_can_vanish && (left <= right || !right_can_vanish);
    const double larger = std::max(std::fabs(left), std::fabs(right));
    const bool decided = !left_can_vanish || !right_can_vanish || larger == 0.0;
    choice.ambiguity[p] = decided ? 0.0 : std::min(std::fabs(left), std::fabs(right)) / larger;
  }
  return choice;
}

std::vector<bool> NlpAssembly::identifyActiveSet(const double* x) const {
  ActiveSetChoice choice = chooseActiveSet(x);
  return choice.valid ? choice.left_is_zero : std::vector<bool>();
}

bool NlpAssembly::fixActiveSet(const double* x, int flip) {
  releaseActiveSet();
  const int pairs = static_cast<int>(complementarities_.size());
  ActiveSetChoice choice = chooseActiveSet(x);
  if (!choice.valid) return false;
  std::vector<bool>& left_is_zero = choice.left_is_zero;
  const std::vector<double>& ambiguity = choice.ambiguity;
  if (flip >= 0) {
    std::vector<int> order(pairs);
    for (int p = 0; p < pairs; ++p) order[p] = p;
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return ambiguity[a] > ambiguity[b]; });
    // Only pairs whose sides are comparable are worth a retry; the rest are decided.
    if (flip >= pairs || ambiguity[order[flip]] < 1e-3) return false;
    left_is_zero[order[flip]] = !left_is_zero[order[flip]];
  }
  return fixPairs(left_is_zero, choice.biactive, x);
}

bool NlpAssembly::fixGivenActiveSet(const std::vector<bool>& left_is_zero, const double* x) {
  return fixPairs(left_is_zero, std::vector<bool>(left_is_zero.size(), false), x);
}

bool NlpAssembly::fixGivenActiveSet(const std::vector<bool>& left_is_zero, const double* x,
                                    const std::vector<int>& left_free) {
  return fixPairs(left_is_zero, std::vector<bool>(left_is_zero.size(), false), x, left_free);
}

bool NlpAssembly::fixPairs(const std::vector<bool>& left_is_zero, const std::vector<bool>& biactive,
                           const double* x, const std::vector<int>& left_free) {
  releaseActiveSet();
  const int pairs = static_cast<int>(complementarities_.size());
  if (static_cast<int>(left_is_zero.size()) != pairs) return false;
  std::vector<int> to_fix;
  std::vector<bool> biactive_variables;
  for (int p = 0; p < pairs; ++p) {
    const Complementarity& comp = complementarities_[p];
    if (biactive[p]) {
      // Both sides stay free (>= 0): the pair's part of the relaxed NLP of the MPCC.
      if (biactive_variables.empty()) biactive_variables.assign(numVariables(), false);
      for (const LinearExpression* side : {&comp.left, &comp.right}) {
        for (const LinearTerm& t : *side) biactive_variables[t.variable] = true;
      }
      continue;
    }
    for (const LinearTerm& t : left_is_zero[p] ? comp.left : comp.right) {
      if (std::count(left_free.begin(), left_free.end(), t.variable)) continue;
      if (fixed(t.variable)) {
        // Data: it must be (negligibly close to) zero to be the zero side.
        if (!fixedNearZero(t.variable)) return false;
        continue;
      }
      if (t.coefficient <= 0.0 || x_lower_[t.variable] != 0.0) return false;
      to_fix.push_back(t.variable);
    }
  }
  saved_x_lower_ = x_lower_;
  saved_x_upper_ = x_upper_;
  saved_g_lower_ = g_lower_;
  saved_g_upper_ = g_upper_;
  for (int variable : to_fix) x_upper_[variable] = 0.0;
  for (int row : complementarity_rows_) g_upper_[row] = kInfinity;
  fixed_left_ = left_is_zero;
  biactive_pairs_ = biactive;
  biactive_variables_ = std::move(biactive_variables);
  if (hook_) hook_(x);
  return true;
}

std::vector<bool> NlpAssembly::flipBiactivePairs(const double* x) const {
  if (saved_x_lower_.empty()) throw std::logic_error("flipBiactivePairs: no active set is fixed");
  double largest = 0.0;
  std::vector<double> free_sides(complementarities_.size());
  for (size_t p = 0; p < complementarities_.size(); ++p) {
    const Complementarity& comp = complementarities_[p];
    if (biactive_pairs_[p]) continue;  // no side fixed, nothing to flip
    free_sides[p] = fixed_left_[p] ? comp.right_weight * linearValue(comp.right, x)
                                   : comp.left_weight * linearValue(comp.left, x);
    largest = std::max(largest, std::fabs(free_sides[p]));
  }
  std::vector<bool> flipped = fixed_left_;
  bool any = false;
  for (size_t p = 0; p < complementarities_.size(); ++p) {
    if (biactive_pairs_[p]) continue;
    if (free_sides[p] <= kBiactiveFraction * largest) {
      flipped[p] = !flipped[p];
      any = true;
    }
  }
  return any ? flipped : std::vector<bool>();
}

void NlpAssembly::releaseActiveSet() {
  if (saved_x_lower_.empty()) return;
  x_lower_.swap(saved_x_lower_);
  x_upper_.swap(saved_x_upper_);
  g_lower_.swap(saved_g_lower_);
  g_upper_.swap(saved_g_upper_);
  saved_x_lower_.clear();
  biactive_variables_.clear();
}

double NlpAssembly::biactiveDescent(const double* x, const double* multipliers) const {
  if (saved_x_lower_.empty()) throw std::logic_error("biactiveDescent: no active set is fixed");
  std::vector<double> gradient(numVariables());
  objectiveGradient(x, gradient.data());
  double scale = 1.0;
  for (double g : gradient) scale = std::max(scale, std::fabs(g));
  const std::vector<double> lagrangian_gradient = lagrangianGradient(*this, x, multipliers);
  double descent = 0.0;
  for (size_t p = 0; p < complementarities_.size(); ++p) {
    // A pair left biactive has both sides free: Ipopt's bound multipliers are its signs.
    if (biactive_pairs_[p]) continue;
    const Complementarity& comp = complementarities_[p];
    const LinearExpression& fixed = fixed_left_[p] ? comp.left : comp.right;
    const LinearExpression& free = fixed_left_[p] ? comp.right : comp.left;
    if (linearValue(free, x) > kNegligibleFixedValue) continue;
    for (const LinearTerm& t : fixed) {
      // Data stays fixed; a side fixed by the active set was released from saved bounds [0, .].
      if (saved_x_lower_[t.variable] == saved_x_upper_[t.variable]) continue;
      descent = std::max(descent, -lagrangian_gradient[t.variable] / scale);
    }
  }
  return descent;
}

std::vector<FixedPair> NlpAssembly::fixedPairs() const {
  if (saved_x_lower_.empty()) throw std::logic_error("fixedPairs: no active set is fixed");
  std::vector<FixedPair> pairs;
  pairs.reserve(complementarities_.size());
  for (size_t p = 0; p < complementarities_.size(); ++p) {
    const Complementarity& comp = complementarities_[p];
    if (biactive_pairs_[p] || fixed_left_[p]) {
      pairs.push_back({comp.left, comp.right, true, biactive_pairs_[p]});
    } else {
      pairs.push_back({comp.right, comp.left, false, false});
    }
  }
  return pairs;
}

void NlpAssembly::boundsBeforeActiveSet(double* x_lower, double* x_upper) const {
  if (saved_x_lower_.empty()) {
    throw std::logic_error("boundsBeforeActiveSet: no active set is fixed");
  }
  std::copy(saved_x_lower_.begin(), saved_x_lower_.end(), x_lower);
  std::copy(saved_x_upper_.begin(), saved_x_upper_.end(), x_upper);
}

double NlpAssembly::complementarityResidual(const double* x) const {
  return largestProduct(x, false);
}

double NlpAssembly::complementarityResidualOfUnknowns(const double* x,
                                                      const std::vector<int>& left_free) const {
  return largestProduct(x, true, left_free);
}

double NlpAssembly::largestProduct(const double* x, bool without_negligible_fixed,
                                   const std::vector<int>& left_out) const {
  const auto sideValue = [&](const LinearExpression& side) {
    double value = 0.0;
    for (const LinearTerm& t : side) {
      const bool out = std::count(left_out.begin(), left_out.end(), t.variable) > 0;
      if (!out && !(without_negligible_fixed && fixedNearZero(t.variable))) {
        value += t.coefficient * x[t.variable];
      }
    }
    return value;
  };
  double residual = 0.0;
  for (const Complementarity& comp : complementarities_) {
    residual = std::max(residual, std::fabs(sideValue(comp.left) * sideValue(comp.right)));
  }
  return residual;
}

std::vector<int> NlpAssembly::complementarityRowsWith(const std::vector<int>& variables) const {
  std::vector<int> rows;
  if (variables.empty()) return rows;  // every accepted active-set step asks
  for (const Complementarity& comp : complementarities_) {
    for (const LinearExpression* side : {&comp.left, &comp.right}) {
      const bool has = std::any_of(side->begin(), side->end(), [&](const LinearTerm& t) {
        return std::count(variables.begin(), variables.end(), t.variable) > 0;
      });
      if (has && (rows.empty() || rows.back() != comp.row)) rows.push_back(comp.row);
    }
  }
  return rows;
}

double NlpAssembly::equalityResidual(const double* x) const {
  std::vector<double> g(numConstraints());
  constraints(x, g.data());
  double residual = 0.0;
  for (int i = 0; i < numConstraints(); ++i) {
    if (g_lower_[i] == g_upper_[i]) residual = std::max(residual, std::fabs(g[i] - g_lower_[i]));
  }
  return residual;
}

}  // namespace fesd
