#include "fesd_trajopt/scene/disc_scene.h"

#include <map>
#include <stdexcept>

#include "fesd_trajopt/function/pattern_builder.h"

namespace fesd {
namespace {

/// Per pair: the state indices and fixed data its constraint needs.
struct PairGeometry {
  ContactPair::Kind kind;
  int first;              ///< state index of the body's position
  int second = -1;        ///< state index of the other body (body-body only)
  Eigen::VectorXd point;  ///< obstacle centre or wall normal
  double constant = 0.0;  ///< (R_i + R_j)^2, (R_i + R_o)^2, or offset + R_i
  /// A typical |grad c| on the boundary c = 0 (DcsModel's constraint scale): 2 (R_i + R_j), or 1
  /// for a wall.
  double gradient_scale = 1.0;
};

std::vector<PairGeometry> geometry(const DiscScene& scene, const std::vector<ContactPair>& pairs) {
  std::vector<PairGeometry> result;
  for (const ContactPair& pair : pairs) {
    const SceneBody& body = scene.bodies().at(pair.body);
    PairGeometry g;
    g.kind = pair.kind;
    g.first = scene.stateIndex(pair.body);
    switch (pair.kind) {
      case ContactPair::Kind::kBody: {
        const SceneBody& other = scene.bodies().at(pair.other);
        g.second = scene.stateIndex(pair.other);
        g.constant = (body.radius + other.radius) * (body.radius + other.radius);
        g.gradient_scale = 2.0 * (body.radius + other.radius);
        break;
      }
      case ContactPair::Kind::kObstacle: {
        const SceneObstacle& obstacle = scene.obstacles().at(pair.other);
        g.point = obstacle.position;
        g.constant = (body.radius + obstacle.radius) * (body.radius + obstacle.radius);
        g.gradient_scale = 2.0 * (body.radius + obstacle.radius);
        break;
      }
      case ContactPair::Kind::kWall: {
        const SceneWall& wall = scene.walls().at(pair.other);
        g.point = wall.normal;
        g.constant = wall.offset + body.radius;
        break;
      }
    }
    result.push_back(std::move(g));
  }
  return result;
}

/// Sparse gradients of the pair constraints: for pair k, entries (state index, value) in a fixed
/// order; the same order serves the constraint Jacobian and the velocity's lambda columns.
class PairGradients {
 public:
  PairGradients(int dimension, std::vector<PairGeometry> pairs)
      : dimension_(dimension), pairs_(std::move(pairs)) {
    for (int k = 0; k < static_cast<int>(pairs_.size()); ++k) {
      const PairGeometry& g = pairs_[k];
      for (int d = 0; d < dimension_; ++d) {
        if (g.kind == ContactPair::Kind::kWall && g.point(d) == 0.0) continue;
        entries_.push_back({k, g.first + d});
      }
      if (g.kind == ContactPair::Kind::kBody) {
        for (int d = 0; d < dimension_; ++d) entries_.push_back({k, g.second + d});
      }
    }
  }

  struct Entry {
    int pair, state;
  };
  const std::vector<Entry>& entries() const { return entries_; }
  const std::vector<PairGeometry>& pairs() const { return pairs_; }
  int dimension() const { return dimension_; }

  double value(int k, const double* x) const {
    const PairGeometry& g = pairs_[k];
    if (g.kind == ContactPair::Kind::kWall) {
      double dot = 0.0;
      for (int d = 0; d < dimension_; ++d) dot += g.point(d) * x[g.first + d];
      return dot - g.constant;
    }
    double squared = 0.0;
    for (int d = 0; d < dimension_; ++d) {
      const double difference = x[g.first + d] - otherCoordinate(g, x, d);
      squared += difference * difference;
    }
    return squared - g.constant;
  }

  /// Gradient entries in entries() order.
  void gradients(const double* x, double* values) const {
    int e = 0;
    for (int k = 0; k < static_cast<int>(pairs_.size()); ++k) {
      const PairGeometry& g = pairs_[k];
      for (int d = 0; d < dimension_; ++d) {
        if (g.kind == ContactPair::Kind::kWall) {
          if (g.point(d) != 0.0) values[e++] = g.point(d);
        } else {
          values[e++] = 2.0 * (x[g.first + d] - otherCoordinate(g, x, d));
        }
      }
      if (g.kind == ContactPair::Kind::kBody) {
        for (int d = 0; d < dimension_; ++d) {
          values[e++] = -2.0 * (x[g.first + d] - x[g.second + d]);
        }
      }
    }
  }

  /// The constant second derivatives: (state a, state b, d2c/dadb) with a >= b, per pair.
  std::vector<std::tuple<int, int, double>> secondDerivatives(int k) const {
    const PairGeometry& g = pairs_[k];
    std::vector<std::tuple<int, int, double>> result;
    if (g.kind == ContactPair::Kind::kWall) return result;
    for (int d = 0; d < dimension_; ++d) {
      result.emplace_back(g.first + d, g.first + d, 2.0);
      if (g.kind == ContactPair::Kind::kBody) {
        result.emplace_back(g.second + d, g.second + d, 2.0);
        result.emplace_back(std::max(g.first, g.second) + d, std::min(g.first, g.second) + d, -2.0);
      }
    }
    return result;
  }

 private:
  double otherCoordinate(const PairGeometry& g, const double* x, int d) const {
    return g.kind == ContactPair::Kind::kBody ? x[g.second + d] : g.point(d);
  }

  int dimension_;
  std::vector<PairGeometry> pairs_;
  std::vector<Entry> entries_;
};

/// c(x) for the chosen pairs.
class SceneConstraints : public SmoothFunction {
 public:
  SceneConstraints(int state_size, std::shared_ptr<const PairGradients> gradients)
      : state_size_(state_size), gradients_(std::move(gradients)) {
    for (const auto& entry : gradients_->entries()) jacobian_.add(entry.pair, entry.state);
    PatternBuilder hessian;
    for (int k = 0; k < outputSize(); ++k) {
      for (const auto& [a, b, value] : gradients_->secondDerivatives(k)) {
        hessian_terms_.push_back({hessian.slot(a, b), k, value});
      }
    }
    hessian_ = hessian.pattern;
  }

  int inputSize() const override { return state_size_; }
  int outputSize() const override { return static_cast<int>(gradients_->pairs().size()); }
  void evaluate(const double* x, double* c) const override {
    for (int k = 0; k < outputSize(); ++k) c[k] = gradients_->value(k, x);
  }
  const SparsityPattern& jacobianPattern() const override { return jacobian_; }
  void evaluateJacobian(const double* x, double* values) const override {
    gradients_->gradients(x, values);
  }
  const SparsityPattern& hessianPattern() const override { return hessian_; }
  void evaluateHessian(const double*, const double* weights, double* values) const override {
    std::fill(values, values + hessian_.nonzeros(), 0.0);
    for (const HessianTerm& t : hessian_terms_) values[t.slot] += weights[t.pair] * t.value;
  }

 private:
  struct HessianTerm {
    int slot, pair;
    double value;
  };
  int state_size_;
  std::shared_ptr<const PairGradients> gradients_;
  SparsityPattern jacobian_, hessian_;
  std::vector<HessianTerm> hessian_terms_;
};

/// v(x, u, lambda) = B u + sum_k lambda_k grad c_k(x).
class SceneVelocity : public SmoothFunction {
 public:
  SceneVelocity(int state_size, const std::vector<std::pair<int, int>>& actuation,
                std::shared_ptr<const PairGradients> gradients, int control_size)
      : nx_(state_size),
        nu_(control_size),
        gradients_(std::move(gradients)),
        scratch_(gradients_->entries().size()) {
    PatternBuilder jacobian;
    for (const auto& [state, control] : actuation) {
      actuation_slots_.push_back(jacobian.slot(state, nx_ + control));
    }
    const int nc = static_cast<int>(gradients_->pairs().size());
    for (int k = 0; k < nc; ++k) {  // sum_k lambda_k Hess c_k, into the x block
      for (const auto& [a, b, value] : gradients_->secondDerivatives(k)) {
        curvature_terms_.push_back({jacobian.slot(a, b), k, value});
        if (a != b) curvature_terms_.push_back({jacobian.slot(b, a), k, value});
      }
    }
    for (const auto& entry : gradients_->entries()) {  // grad c_k, the lambda_k column
      gradient_slots_.push_back(jacobian.slot(entry.state, nx_ + nu_ + entry.pair));
    }
    jacobian_ = jacobian.pattern;
    // d^2 (w . v) / d lambda_k dx = Hess c_k w: row lambda_k, the pair's state columns.
    PatternBuilder hessian;
    for (int k = 0; k < nc; ++k) {
      for (const auto& [a, b, value] : gradients_->secondDerivatives(k)) {
        mixed_terms_.push_back({hessian.slot(nx_ + nu_ + k, a), k, b, value});
        if (a != b) mixed_terms_.push_back({hessian.slot(nx_ + nu_ + k, b), k, a, value});
      }
    }
    hessian_ = hessian.pattern;
    for (const auto& [state, control] : actuation) actuation_.push_back({state, control});
  }

  int inputSize() const override {
    return nx_ + nu_ + static_cast<int>(gradients_->pairs().size());
  }
  int outputSize() const override { return nx_; }

  void evaluate(const double* z, double* v) const override {
    std::fill(v, v + nx_, 0.0);
    for (const auto& [state, control] : actuation_) v[state] += z[nx_ + control];
    gradients_->gradients(z, scratch_.data());
    const auto& entries = gradients_->entries();
    for (size_t e = 0; e < entries.size(); ++e) {
      v[entries[e].state] += z[nx_ + nu_ + entries[e].pair] * scratch_[e];
    }
  }

  const SparsityPattern& jacobianPattern() const override { return jacobian_; }
  void evaluateJacobian(const double* z, double* values) const override {
    std::fill(values, values + jacobian_.nonzeros(), 0.0);
    for (int slot : actuation_slots_) values[slot] += 1.0;
    for (const Term& t : curvature_terms_) values[t.slot] += z[nx_ + nu_ + t.pair] * t.value;
    gradients_->gradients(z, scratch_.data());
    for (size_t e = 0; e < gradient_slots_.size(); ++e) values[gradient_slots_[e]] += scratch_[e];
  }

  const SparsityPattern& hessianPattern() const override { return hessian_; }
  void evaluateHessian(const double*, const double* weights, double* values) const override {
    std::fill(values, values + hessian_.nonzeros(), 0.0);
    for (const MixedTerm& t : mixed_terms_) values[t.slot] += t.value * weights[t.weight_state];
  }

 private:
  struct Term {
    int slot, pair;
    double value;
  };
  struct MixedTerm {
    int slot, pair, weight_state;
    double value;
  };
  int nx_, nu_;
  std::shared_ptr<const PairGradients> gradients_;
  std::vector<std::pair<int, int>> actuation_;
  std::vector<int> actuation_slots_, gradient_slots_;
  std::vector<Term> curvature_terms_;
  std::vector<MixedTerm> mixed_terms_;
  SparsityPattern jacobian_, hessian_;
  mutable std::vector<double> scratch_;
};

}  // namespace

int DiscScene::controlSize() const {
  int actuated = 0;
  for (const SceneBody& body : bodies_) actuated += body.actuated;
  return dimension_ * actuated;
}

int DiscScene::controlIndex(int body) const {
  if (!bodies_.at(body).actuated) return -1;
  int actuated_before = 0;
  for (int b = 0; b < body; ++b) actuated_before += bodies_[b].actuated;
  return dimension_ * actuated_before;
}

Eigen::VectorXd DiscScene::initialState() const {
  Eigen::VectorXd x(stateSize());
  for (size_t b = 0; b < bodies_.size(); ++b) {
    x.segment(stateIndex(static_cast<int>(b)), dimension_) = bodies_[b].position;
  }
  return x;
}

std::vector<ContactPair> DiscScene::allPairs() const {
  std::vector<ContactPair> pairs;
  const int n = static_cast<int>(bodies_.size());
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) pairs.push_back({i, ContactPair::Kind::kBody, j});
    for (int o = 0; o < static_cast<int>(obstacles_.size()); ++o) {
      pairs.push_back({i, ContactPair::Kind::kObstacle, o});
    }
    for (int w = 0; w < static_cast<int>(walls_.size()); ++w) {
      pairs.push_back({i, ContactPair::Kind::kWall, w});
    }
  }
  return pairs;
}

double DiscScene::constraintValue(const ContactPair& pair, const Eigen::VectorXd& x) const {
  return PairGradients(dimension_, geometry(*this, {pair})).value(0, x.data());
}

std::string DiscScene::pairName(const ContactPair& pair) const {
  const std::string& body = bodies_.at(pair.body).name;
  switch (pair.kind) {
    case ContactPair::Kind::kBody:
      return body + "/" + bodies_.at(pair.other).name;
    case ContactPair::Kind::kObstacle:
      return body + "/" + obstacles_.at(pair.other).name;
    case ContactPair::Kind::kWall:
      return body + "/" + walls_.at(pair.other).name;
  }
  return body;
}

std::shared_ptr<const DcsModel> DiscScene::model(const std::vector<ContactPair>& pairs) const {
  if (dimension_ != 2 && dimension_ != 3) {
    throw std::invalid_argument("DiscScene: dimension must be 2 or 3");
  }
  for (const SceneBody& body : bodies_) {
    if (body.position.size() != dimension_) {
      throw std::invalid_argument("DiscScene: body '" + body.name + "' has the wrong dimension");
    }
  }
  std::vector<PairGeometry> pair_geometry = geometry(*this, pairs);
  Eigen::VectorXd scales(pair_geometry.size());
  for (size_t k = 0; k < pair_geometry.size(); ++k) scales(k) = pair_geometry[k].gradient_scale;
  auto gradients = std::make_shared<const PairGradients>(dimension_, std::move(pair_geometry));
  std::vector<std::pair<int, int>> actuation;  // (state index, control index) per coordinate
  for (int b = 0; b < static_cast<int>(bodies_.size()); ++b) {
    if (!bodies_[b].actuated) continue;
    for (int d = 0; d < dimension_; ++d) {
      actuation.emplace_back(stateIndex(b) + d, controlIndex(b) + d);
    }
  }
  const int nc = static_cast<int>(pairs.size());
  return std::make_shared<DcsModel>(
      stateSize(), controlSize(), nc,
      std::make_shared<SceneVelocity>(stateSize(), actuation, gradients, controlSize()),
      std::make_shared<SceneConstraints>(stateSize(), gradients), "disc_scene", scales);
}

}  // namespace fesd
