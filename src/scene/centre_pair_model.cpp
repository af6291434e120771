#include "fesd_trajopt/scene/centre_pair_model.h"

#include <algorithm>

#include "fesd_trajopt/function/pattern_builder.h"

namespace fesd {
namespace {

/// The union of a pair's variables and where each side's variables sit in it.
struct PairLayout {
  std::vector<int> variables;  ///< ascending state indices
  std::vector<int> a_slots, b_slots;
  bool curved = false;  ///< a robot sphere or a turning body is involved: c has third derivatives
  /// The structural nonzeros in local variables (addStructuralEntries): of grad c, of Hess c
  /// (both triangles) and the rows of Hess c that hold any.
  std::vector<int> gradient_entries, hessian_rows;
  std::vector<std::pair<int, int>> hessian_entries;
  /// A translating pair's Hessian at hessian_entries: constant (+-2).
  std::vector<double> hessian_constants;
};

/// A curved pair's derivatives are dense. A translating centre moves its coordinate d with one
/// variable, so c couples coordinate d of the two sides only: per d, (a, a), and with a second
/// centre (b, b), (b, a), (a, b); a wall's gradient lacks the coordinates its normal lacks and
/// its Hessian is zero. No zero reaches the NLP's sparsity.
void addStructuralEntries(const CentrePair& pair, PairLayout& layout) {
  const int n = static_cast<int>(layout.variables.size());
  if (layout.curved) {
    for (int i = 0; i < n; ++i) {
      layout.gradient_entries.push_back(i);
      layout.hessian_rows.push_back(i);
      for (int j = 0; j < n; ++j) layout.hessian_entries.emplace_back(i, j);
    }
    return;
  }
  const bool wall = pair.kind == CentrePair::Kind::kWall;
  for (size_t d = 0; d < layout.a_slots.size(); ++d) {
    const int a = layout.a_slots[d];
    if (!wall || pair.point(d) != 0.0) layout.gradient_entries.push_back(a);
    if (wall) continue;
    layout.hessian_rows.push_back(a);
    layout.hessian_entries.emplace_back(a, a);
    layout.hessian_constants.push_back(2.0);
    if (pair.kind != CentrePair::Kind::kCentre) continue;
    const int b = layout.b_slots[d];
    layout.hessian_rows.push_back(b);
    layout.hessian_entries.emplace_back(b, b);
    layout.hessian_entries.emplace_back(std::max(a, b), std::min(a, b));
    layout.hessian_entries.emplace_back(std::min(a, b), std::max(a, b));
    layout.hessian_constants.insert(layout.hessian_constants.end(), {2.0, -2.0, -2.0});
  }
  layout.gradient_entries.insert(layout.gradient_entries.end(), layout.b_slots.begin(),
                                 layout.b_slots.end());
}

PairLayout layoutOf(const CentreEvaluator& evaluator, const CentrePair& pair) {
  PairLayout layout;
  const std::vector<int> a = evaluator.variables(pair.a);
  const std::vector<int> b =
      pair.kind == CentrePair::Kind::kCentre ? evaluator.variables(pair.b) : std::vector<int>{};
  std::vector<int> all = a;
  all.insert(all.end(), b.begin(), b.end());
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  layout.variables = all;
  const auto slot = [&](int v) {
    return static_cast<int>(std::lower_bound(all.begin(), all.end(), v) - all.begin());
  };
  for (int v : a) layout.a_slots.push_back(slot(v));
  for (int v : b) layout.b_slots.push_back(slot(v));
  const auto is_curved = [](const CollisionCentre& c) {
    return c.source != CollisionCentre::Source::kFreeBody;
  };
  layout.curved =
      is_curved(pair.a) || (pair.kind == CentrePair::Kind::kCentre && is_curved(pair.b));
  addStructuralEntries(pair, layout);
  return layout;
}

/// A curved pair's buffers, sized once for its variables (n local, na and nb per side): its
/// evaluations write into them, so that the NLP's evaluations allocate nothing per pair.
struct PairWork {
  PairWork() = default;  // a translating pair's: empty
  explicit PairWork(const PairLayout& layout) {
    const int n = static_cast<int>(layout.variables.size());
    const int na = static_cast<int>(layout.a_slots.size());
    const int nb = static_cast<int>(layout.b_slots.size());
    a_jacobian.resize(3, na);
    b_jacobian.resize(3, nb);
    jacobian.resize(3, n);
    gradient.resize(n);
    direction.resize(n);
    mixed.resize(n);
    a_direction.resize(na);
    b_direction.resize(nb);
    a_block.resize(na, na);
    b_block.resize(nb, nb);
    for (Eigen::MatrixXd* m : {&hessian, &curvature, &gd, &third, &third_derivative}) {
      m->resize(n, n);
    }
    g.resize(n, 3);
  }
  Eigen::Matrix3Xd a_jacobian, b_jacobian, jacobian;
  Eigen::Vector3d difference = Eigen::Vector3d::Zero();
  /// direction: the weights a caller contracts with (local variables); mixed: Hess c times them.
  Eigen::VectorXd gradient, direction, mixed, a_direction, b_direction;
  Eigen::MatrixXd a_block, b_block, hessian, curvature, g, gd, third, third_derivative;
};

/// A curved pair's derivatives in its local variables at the evaluator's state, in its PairWork.
class LocalPair {
 public:
  LocalPair(const CentreEvaluator& evaluator, const CentrePair& pair, const PairLayout& layout,
            PairWork& work)
      : evaluator_(evaluator), pair_(pair), layout_(layout), work_(work) {
    work_.jacobian.setZero();
    evaluator.jacobian(pair.a, work_.a_jacobian);
    scatterColumns(work_.a_jacobian, layout.a_slots, 1.0);
    work_.difference = evaluator.position(pair.a);
    if (pair.kind == CentrePair::Kind::kCentre) {
      evaluator.jacobian(pair.b, work_.b_jacobian);
      scatterColumns(work_.b_jacobian, layout.b_slots, -1.0);
      work_.difference -= evaluator.position(pair.b);
    } else if (pair.kind == CentrePair::Kind::kPoint) {
      work_.difference -= pair.point;
    }
  }

  const Eigen::VectorXd& gradient() const {
    if (pair_.kind == CentrePair::Kind::kWall) {
      work_.gradient.noalias() = work_.jacobian.transpose() * pair_.point;
    } else {
      work_.gradient.noalias() = 2.0 * work_.jacobian.transpose() * work_.difference;
    }
    return work_.gradient;
  }

  const Eigen::MatrixXd& hessian() const {
    curvature(pair_.kind == CentrePair::Kind::kWall ? Eigen::Vector3d(pair_.point)
                                                    : work_.difference);
    if (pair_.kind == CentrePair::Kind::kWall) {
      work_.hessian = work_.curvature;
      return work_.hessian;
    }
    work_.hessian.noalias() = work_.jacobian.transpose() * work_.jacobian;
    work_.hessian += work_.curvature;
    work_.hessian *= 2.0;
    return work_.hessian;
  }

  /// d/dx (Hess c) along w (local variables): the third derivatives of c contracted with w.
  const Eigen::MatrixXd& thirdDerivative(const Eigen::VectorXd& w) const {
    Eigen::MatrixXd& result = work_.third_derivative;
    if (pair_.kind == CentrePair::Kind::kWall) {
      third(pair_.point, w);
      result = work_.third;
      return result;
    }
    // c_ij = 2 sum_m (D_mi D_mj + d_m H_m,ij); differentiating along w gives
    // 2 (G D + D^T G^T + H[D w] + T[d, w]) with column m of G the vector H_m w.
    for (int m = 0; m < 3; ++m) {
      curvature(Eigen::Vector3d::Unit(m));
      work_.g.col(m).noalias() = work_.curvature * w;
    }
    work_.gd.noalias() = work_.g * work_.jacobian;
    result = work_.gd;
    result += work_.gd.transpose();
    curvature(work_.jacobian * w);
    result += work_.curvature;
    third(work_.difference, w);
    result += work_.third;
    result *= 2.0;
    return result;
  }

 private:
  void scatterColumns(const Eigen::Matrix3Xd& columns, const std::vector<int>& slots, double sign) {
    for (size_t c = 0; c < slots.size(); ++c) work_.jacobian.col(slots[c]) += sign * columns.col(c);
  }

  /// Hess (w . d(x)) in the local variables, into work_.curvature.
  void curvature(const Eigen::Vector3d& w) const {
    work_.curvature.setZero();
    evaluator_.weightedHessian(pair_.a, w, work_.a_block);
    scatterBlock(work_.a_block, layout_.a_slots, 1.0, work_.curvature);
    if (pair_.kind == CentrePair::Kind::kCentre) {
      evaluator_.weightedHessian(pair_.b, w, work_.b_block);
      scatterBlock(work_.b_block, layout_.b_slots, -1.0, work_.curvature);
    }
  }

  /// d/dx Hess (w . d(x)) along v (local variables), w fixed, into work_.third.
  void third(const Eigen::Vector3d& w, const Eigen::VectorXd& v) const {
    work_.third.setZero();
    gather(v, layout_.a_slots, work_.a_direction);
    evaluator_.weightedThirdDerivative(pair_.a, w, work_.a_direction, work_.a_block);
    scatterBlock(work_.a_block, layout_.a_slots, 1.0, work_.third);
    if (pair_.kind == CentrePair::Kind::kCentre) {
      gather(v, layout_.b_slots, work_.b_direction);
      evaluator_.weightedThirdDerivative(pair_.b, w, work_.b_direction, work_.b_block);
      scatterBlock(work_.b_block, layout_.b_slots, -1.0, work_.third);
    }
  }

  static void gather(const Eigen::VectorXd& v, const std::vector<int>& slots,
                     Eigen::VectorXd& into) {
    for (size_t s = 0; s < slots.size(); ++s) into(s) = v(slots[s]);
  }

  static void scatterBlock(const Eigen::MatrixXd& block, const std::vector<int>& slots, double sign,
                           Eigen::MatrixXd& into) {
    for (size_t r = 0; r < slots.size(); ++r) {
      for (size_t c = 0; c < slots.size(); ++c) into(slots[r], slots[c]) += sign * block(r, c);
    }
  }

  const CentreEvaluator& evaluator_;
  const CentrePair& pair_;
  const PairLayout& layout_;
  PairWork& work_;
};

/// The pairs' shared state: layouts and the (mutable) evaluator.
class PairSet {
 public:
  explicit PairSet(const CentrePairSystem& system)
      : system_(system), evaluator_(system.robot, system.dimension) {
    for (const CentrePair& pair : system_.pairs) {
      layouts_.push_back(layoutOf(evaluator_, pair));
      work_.push_back(layouts_.back().curved ? PairWork(layouts_.back()) : PairWork());
    }
  }
  int size() const { return static_cast<int>(system_.pairs.size()); }
  const CentrePairSystem& system() const { return system_; }
  /// Another thread's: its own evaluator (kinematics cache) and buffers.
  std::shared_ptr<const PairSet> threadCopy(ThreadCopies& copies) const {
    return copies.of<PairSet>(this, [&] { return std::make_shared<const PairSet>(system_); });
  }
  const PairLayout& layout(int k) const { return layouts_[k]; }
  /// Sets the state; then local(k) gives pair k's derivatives there, value(k) its value alone.
  void setState(const double* x) const { evaluator_.setState(x); }
  /// Pair k's derivatives at the state set: k must be curved (a sphere or a turning body).
  LocalPair local(int k) const {
    return LocalPair(evaluator_, system_.pairs[k], layouts_[k], work_[k]);
  }
  /// Curved pair k's buffer for the weights a caller contracts its derivatives with.
  Eigen::VectorXd& direction(int k) const { return work_[k].direction; }
  Eigen::VectorXd& mixed(int k) const { return work_[k].mixed; }
  double value(int k) const { return centrePairValue(evaluator_, system_.pairs[k]); }

  /// Pair k's gradient at its gradient_entries and its Hessian at its hessian_entries (either
  /// may be null). A curved pair's from one LocalPair; a translating pair's without one: no
  /// allocation in the evaluations' inner loop (a scene of discs has only such pairs).
  void derivatives(int k, double* gradient, double* hessian) const {
    const PairLayout& layout = layouts_[k];
    if (layout.curved) {
      const LocalPair local = this->local(k);
      if (gradient) {
        const Eigen::VectorXd& g = local.gradient();
        for (size_t e = 0; e < layout.gradient_entries.size(); ++e) {
          gradient[e] = g(layout.gradient_entries[e]);
        }
      }
      if (hessian) {
        const Eigen::MatrixXd& h = local.hessian();
        for (size_t e = 0; e < layout.hessian_entries.size(); ++e) {
          hessian[e] = h(layout.hessian_entries[e].first, layout.hessian_entries[e].second);
        }
      }
      return;
    }
    if (hessian) {
      std::copy(layout.hessian_constants.begin(), layout.hessian_constants.end(), hessian);
    }
    if (gradient) translatingGradient(k, gradient);
  }

  /// The most gradient or Hessian entries of a pair: the size of the buffers above.
  size_t maxEntries() const {
    size_t most = 0;
    for (const PairLayout& layout : layouts_) {
      most = std::max({most, layout.gradient_entries.size(), layout.hessian_entries.size()});
    }
    return most;
  }

 private:
  /// A translating pair's gradient: 2 (p_a - p_b) on a's coordinates, its negative on b's; a
  /// wall's normal on the coordinates it has.
  void translatingGradient(int k, double* values) const {
    const PairLayout& layout = layouts_[k];
    const CentrePair& pair = system_.pairs[k];
    int e = 0;
    if (pair.kind == CentrePair::Kind::kWall) {
      for (size_t d = 0; d < layout.a_slots.size(); ++d) {
        if (pair.point(d) != 0.0) values[e++] = pair.point(d);
      }
      return;
    }
    Eigen::Vector3d difference = evaluator_.position(pair.a);
    difference -= pair.kind == CentrePair::Kind::kCentre ? evaluator_.position(pair.b) : pair.point;
    for (size_t d = 0; d < layout.a_slots.size(); ++d) values[e++] = 2.0 * difference(d);
    for (size_t d = 0; d < layout.b_slots.size(); ++d) values[e++] = -2.0 * difference(d);
  }

  CentrePairSystem system_;
  mutable CentreEvaluator evaluator_;
  std::vector<PairLayout> layouts_;
  mutable std::vector<PairWork> work_;  ///< per pair (empty for a translating one)
};

/// c(x) of every pair.
class CentreConstraints : public SmoothFunction {
 public:
  explicit CentreConstraints(std::shared_ptr<const PairSet> pairs) : pairs_(std::move(pairs)) {
    PatternBuilder hessian;
    for (int k = 0; k < pairs_->size(); ++k) {
      const PairLayout& layout = pairs_->layout(k);
      const std::vector<int>& v = layout.variables;
      for (int i : layout.gradient_entries) jacobian_.add(k, v[i]);
      std::vector<HessianSlot> slots;
      for (size_t e = 0; e < layout.hessian_entries.size(); ++e) {
        const auto [i, j] = layout.hessian_entries[e];
        if (j <= i) slots.push_back({static_cast<int>(e), hessian.slot(v[i], v[j])});
      }
      hessian_slots_.push_back(slots);
    }
    hessian_ = hessian.pattern;
    scratch_.resize(pairs_->maxEntries());
  }

  int inputSize() const override { return pairs_->system().state_size; }
  int outputSize() const override { return pairs_->size(); }
  void evaluate(const double* x, double* c) const override {
    pairs_->setState(x);
    for (int k = 0; k < outputSize(); ++k) c[k] = pairs_->value(k);
  }
  const SparsityPattern& jacobianPattern() const override { return jacobian_; }
  void evaluateJacobian(const double* x, double* values) const override {
    pairs_->setState(x);
    int e = 0;
    for (int k = 0; k < outputSize(); ++k) {
      pairs_->derivatives(k, values + e, nullptr);
      e += static_cast<int>(pairs_->layout(k).gradient_entries.size());
    }
  }
  const SparsityPattern& hessianPattern() const override { return hessian_; }
  std::shared_ptr<const SmoothFunction> threadCopy(ThreadCopies& copies) const override {
    auto copy = std::make_shared<CentreConstraints>(*this);
    copy->pairs_ = pairs_->threadCopy(copies);
    return copy;
  }
  void evaluateHessian(const double* x, const double* weights, double* values) const override {
    std::fill(values, values + hessian_.nonzeros(), 0.0);
    pairs_->setState(x);
    for (int k = 0; k < outputSize(); ++k) {
      if (weights[k] == 0.0) continue;
      pairs_->derivatives(k, nullptr, scratch_.data());
      for (const HessianSlot& e : hessian_slots_[k]) {
        values[e.slot] += weights[k] * scratch_[e.entry];
      }
    }
  }

 private:
  struct HessianSlot {
    int entry, slot;  ///< of the lower triangle's hessian_entries
  };
  std::shared_ptr<const PairSet> pairs_;
  SparsityPattern jacobian_, hessian_;
  std::vector<std::vector<HessianSlot>> hessian_slots_;  ///< per pair
  mutable std::vector<double> scratch_;
};

/// Rows of v(x, u, lambda) = B u + diag(mobility) sum_k lambda_k grad c_k(x): output r is state
/// coordinate rows[r]'s. A coordinate of mobility 0 has the constant 0 (its entries slot -1, left
/// out of the patterns), as has every coordinate but the outputs.
class CentreVelocity : public SmoothFunction {
 public:
  CentreVelocity(std::shared_ptr<const PairSet> pairs, std::vector<double> mobility,
                 const std::vector<int>& rows, bool actuated)
      : pairs_(std::move(pairs)), mobility_(std::move(mobility)) {
    const CentrePairSystem& system = pairs_->system();
    nx_ = system.state_size;
    nu_ = system.control_size;
    outputs_ = static_cast<int>(rows.size());
    mobility_.resize(nx_, 1.0);
    output_.assign(nx_, -1);
    for (int r = 0; r < outputs_; ++r) output_[rows[r]] = r;
    for (int i = 0; i < nx_; ++i) {
      if (mobility_[i] == 0.0) output_[i] = -1;
    }
    PatternBuilder jacobian, hessian;
    if (actuated) actuation_ = system.actuation;
    for (const auto& [state, control] : actuation_) {
      actuation_slots_.push_back(output_[state] < 0 ? -1
                                                    : jacobian.slot(output_[state], nx_ + control));
    }
    for (int k = 0; k < pairs_->size(); ++k) {
      const PairLayout& layout = pairs_->layout(k);
      const std::vector<int>& v = layout.variables;
      const int n = static_cast<int>(v.size());
      PairSlots slots;
      for (const auto& [i, j] : layout.hessian_entries) {
        slots.curvature.push_back(output_[v[i]] < 0 ? -1 : jacobian.slot(output_[v[i]], v[j]));
      }
      for (int i : layout.hessian_rows) slots.mixed.push_back(hessian.slot(nx_ + nu_ + k, v[i]));
      for (int i = 0; layout.curved && i < n; ++i) {
        for (int j = 0; j <= i; ++j) slots.third.push_back(hessian.slot(v[i], v[j]));
      }
      slots_.push_back(slots);
    }
    // The lambda columns after every curvature entry: the x block's entries come first.
    for (int k = 0; k < pairs_->size(); ++k) {
      const PairLayout& layout = pairs_->layout(k);
      for (int i : layout.gradient_entries) {
        const int row = output_[layout.variables[i]];
        slots_[k].gradient.push_back(row < 0 ? -1 : jacobian.slot(row, nx_ + nu_ + k));
      }
    }
    jacobian_ = jacobian.pattern;
    hessian_ = hessian.pattern;
    gradient_.resize(pairs_->maxEntries());
    hessian_values_.resize(pairs_->maxEntries());
  }

  int inputSize() const override { return nx_ + nu_ + pairs_->size(); }
  int outputSize() const override { return outputs_; }
  std::shared_ptr<const SmoothFunction> threadCopy(ThreadCopies& copies) const override {
    auto copy = std::make_shared<CentreVelocity>(*this);
    copy->pairs_ = pairs_->threadCopy(copies);
    return copy;
  }

  void evaluate(const double* z, double* v) const override {
    std::fill(v, v + outputs_, 0.0);
    for (const auto& [state, control] : actuation_) {
      if (output_[state] >= 0) v[output_[state]] += z[nx_ + control];
    }
    pairs_->setState(z);
    for (int k = 0; k < pairs_->size(); ++k) {
      const double lambda = z[nx_ + nu_ + k];
      if (lambda == 0.0) continue;
      const PairLayout& layout = pairs_->layout(k);
      pairs_->derivatives(k, gradient_.data(), nullptr);
      for (size_t e = 0; e < layout.gradient_entries.size(); ++e) {
        const int state = layout.variables[layout.gradient_entries[e]];
        if (output_[state] >= 0) v[output_[state]] += mobility_[state] * lambda * gradient_[e];
      }
    }
  }

  const SparsityPattern& jacobianPattern() const override { return jacobian_; }
  void evaluateJacobian(const double* z, double* values) const override {
    std::fill(values, values + jacobian_.nonzeros(), 0.0);
    for (int slot : actuation_slots_) {
      if (slot >= 0) values[slot] += 1.0;
    }
    pairs_->setState(z);
    for (int k = 0; k < pairs_->size(); ++k) {
      const double lambda = z[nx_ + nu_ + k];
      const PairLayout& layout = pairs_->layout(k);
      pairs_->derivatives(k, gradient_.data(), hessian_values_.data());
      for (size_t e = 0; e < layout.hessian_entries.size(); ++e) {
        const int slot = slots_[k].curvature[e];
        const int row = layout.variables[layout.hessian_entries[e].first];
        if (slot >= 0) values[slot] += mobility_[row] * lambda * hessian_values_[e];
      }
      for (size_t e = 0; e < layout.gradient_entries.size(); ++e) {
        const int slot = slots_[k].gradient[e];
        const int row = layout.variables[layout.gradient_entries[e]];
        if (slot >= 0) values[slot] += mobility_[row] * gradient_[e];
      }
    }
  }

  const SparsityPattern& hessianPattern() const override { return hessian_; }
  void evaluateHessian(const double* z, const double* weights, double* values) const override {
    std::fill(values, values + hessian_.nonzeros(), 0.0);
    pairs_->setState(z);
    for (int k = 0; k < pairs_->size(); ++k) {
      const PairLayout& layout = pairs_->layout(k);
      const int n = static_cast<int>(layout.variables.size());
      // w . v weighs coordinate i's contact term by its mobility (0: held).
      const auto weight = [&](int i) {
        const int row = output_[layout.variables[i]];
        return row < 0 ? 0.0 : mobility_[layout.variables[i]] * weights[row];
      };
      bool weighted = false;
      for (int i = 0; i < n; ++i) weighted = weighted || weight(i) != 0.0;
      if (!weighted) continue;
      if (!layout.curved) {  // d^2 (w . v) / d lambda_k dx = Hess c_k w, Hess c_k constant
        Eigen::Matrix<double, 6, 1> mixed = Eigen::Matrix<double, 6, 1>::Zero();
        for (size_t e = 0; e < layout.hessian_entries.size(); ++e) {
          const auto [i, j] = layout.hessian_entries[e];
          mixed(i) += layout.hessian_constants[e] * weight(j);
        }
        for (size_t r = 0; r < layout.hessian_rows.size(); ++r) {
          values[slots_[k].mixed[r]] += mixed(layout.hessian_rows[r]);
        }
        continue;
      }
      Eigen::VectorXd& w = pairs_->direction(k);
      for (int i = 0; i < n; ++i) w(i) = weight(i);
      const LocalPair local = pairs_->local(k);
      Eigen::VectorXd& mixed = pairs_->mixed(k);
      mixed.noalias() = local.hessian() * w;  // d^2 (w . v) / d lambda_k dx
      for (size_t r = 0; r < layout.hessian_rows.size(); ++r) {
        values[slots_[k].mixed[r]] += mixed(layout.hessian_rows[r]);
      }
      const double lambda = z[nx_ + nu_ + k];
      if (!layout.curved || lambda == 0.0) continue;
      const Eigen::MatrixXd& t = local.thirdDerivative(w);
      int s = 0;
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j <= i; ++j) values[slots_[k].third[s++]] += lambda * t(i, j);
      }
    }
  }

 private:
  struct PairSlots {
    std::vector<int> curvature, gradient, mixed, third;
  };
  std::shared_ptr<const PairSet> pairs_;
  int nx_, nu_, outputs_;
  std::vector<double> mobility_;  ///< per state coordinate
  std::vector<int> output_;       ///< per state coordinate: its output row, -1 for none
  std::vector<std::pair<int, int>> actuation_;
  mutable std::vector<double> gradient_, hessian_values_;  ///< one pair's, PairSet's buffers
  std::vector<int> actuation_slots_;
  std::vector<PairSlots> slots_;
  SparsityPattern jacobian_, hessian_;
};

}  // namespace

double centrePairValue(const CentreEvaluator& evaluator, const CentrePair& pair) {
  // The value alone, without the Jacobians a LocalPair gathers: constraint values are
  // evaluated at every Newton iterate and along every path checked for gaps.
  Eigen::Vector3d difference = evaluator.position(pair.a);
  if (pair.kind == CentrePair::Kind::kCentre) {
    difference -= evaluator.position(pair.b);
  } else if (pair.kind == CentrePair::Kind::kPoint) {
    difference -= pair.point;
  }
  if (pair.kind == CentrePair::Kind::kWall) return pair.point.dot(difference) - pair.constant;
  return difference.squaredNorm() - pair.constant;
}

std::shared_ptr<const DcsModel> centrePairModel(const CentrePairSystem& system,
                                                const std::string& name) {
  auto pairs = std::make_shared<const PairSet>(system);
  std::vector<int> every(system.state_size);
  for (int i = 0; i < system.state_size; ++i) every[i] = i;
  return std::make_shared<DcsModel>(
      system.state_size, system.control_size, static_cast<int>(system.pairs.size()),
      std::make_shared<CentreVelocity>(pairs, system.mobility, every, true),
      std::make_shared<CentreConstraints>(pairs), name, system.constraint_scales);
}

std::shared_ptr<const SmoothFunction> heldCoordinateRates(
    const CentrePairSystem& system, const std::vector<std::pair<int, double>>& held) {
  std::vector<double> direction(system.state_size, 0.0);
  std::vector<int> rows;
  for (const auto& [coordinate, sign] : held) {
    direction[coordinate] = sign;
    rows.push_back(coordinate);
  }
  return std::make_shared<CentreVelocity>(std::make_shared<const PairSet>(system), direction, rows,
                                          false);
}

}  // namespace fesd
