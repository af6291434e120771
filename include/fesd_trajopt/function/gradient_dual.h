#pragma once

#include <cmath>
#include <type_traits>

#include <Eigen/Dense>
#include <unsupported/Eigen/AutoDiff>

namespace fesd {

/// A double as a scalar of type S, through any depth of Eigen::AutoDiffScalar nesting.
template <class S>
struct Constant {
  static S of(double value) { return S(value); }
};
template <class Derivatives>
struct Constant<Eigen::AutoDiffScalar<Derivatives>> {
  static Eigen::AutoDiffScalar<Derivatives> of(double value) {
    return Eigen::AutoDiffScalar<Derivatives>(Constant<typename Derivatives::Scalar>::of(value));
  }
};

/// A forward-mode number carrying a value and a gradient, over any scalar S (double or one of
/// Eigen's AutoDiffScalar types). The model adapter uses it as the innermost derivative level
/// (grad c inside the DCS velocity), because Eigen's AutoDiffScalar nested three deep no longer
/// accepts double constants in user code (x + 1.0 needs two implicit conversions); this type
/// takes them at any depth. User functions must call math functions unqualified
/// (`using std::sin; sin(x)`), as for any AD scalar.
template <class S>
class GradientDual {
 public:
  using Vector = Eigen::Matrix<S, Eigen::Dynamic, 1>;

  GradientDual() : value_(Constant<S>::of(0.0)) {}
  template <class D, std::enable_if_t<std::is_arithmetic_v<D> && !std::is_same_v<D, S>, int> = 0>
  GradientDual(D value) : value_(Constant<S>::of(value)) {}  // NOLINT: constants mix freely
  GradientDual(const S& value, Vector gradient = Vector())   // NOLINT
      : value_(value), gradient_(std::move(gradient)) {}
  /// The i-th of n independent variables.
  static GradientDual variable(const S& value, int n, int i) {
    return GradientDual(value, Vector::Unit(n, i));
  }

  const S& value() const { return value_; }
  /// Empty when the number does not depend on the variables.
  const Vector& gradient() const { return gradient_; }

  /// a * this + b * other, with missing gradients read as zero.
  GradientDual combine(const S& a, const GradientDual& other, const S& b, const S& value) const {
    if (gradient_.size() == 0 && other.gradient_.size() == 0) return GradientDual(value);
    if (gradient_.size() == 0) return GradientDual(value, (other.gradient_ * b).eval());
    if (other.gradient_.size() == 0) return GradientDual(value, (gradient_ * a).eval());
    return GradientDual(value, (gradient_ * a + other.gradient_ * b).eval());
  }
  /// f(this) given f and f' at the value (chain rule).
  GradientDual apply(const S& f, const S& derivative) const {
    if (gradient_.size() == 0) return GradientDual(f);
    return GradientDual(f, (gradient_ * derivative).eval());
  }

  static S one() { return Constant<S>::of(1.0); }

  GradientDual& operator+=(const GradientDual& o) { return *this = *this + o; }
  GradientDual& operator-=(const GradientDual& o) { return *this = *this - o; }
  GradientDual& operator*=(const GradientDual& o) { return *this = *this * o; }
  GradientDual& operator/=(const GradientDual& o) { return *this = *this / o; }

  friend GradientDual operator+(const GradientDual& a, const GradientDual& b) {
    return a.combine(one(), b, one(), a.value_ + b.value_);
  }
  friend GradientDual operator-(const GradientDual& a, const GradientDual& b) {
    return a.combine(one(), b, Constant<S>::of(-1.0), a.value_ - b.value_);
  }
  friend GradientDual operator*(const GradientDual& a, const GradientDual& b) {
    return a.combine(b.value_, b, a.value_, a.value_ * b.value_);
  }
  friend GradientDual operator/(const GradientDual& a, const GradientDual& b) {
    const S inverse = one() / b.value_;
    const S quotient = a.value_ * inverse;
    return a.combine(inverse, b, -quotient * inverse, quotient);
  }
  friend GradientDual operator-(const GradientDual& a) {
    return a.apply(-a.value_, Constant<S>::of(-1.0));
  }
  friend GradientDual operator+(const GradientDual& a) { return a; }

  friend bool operator<(const GradientDual& a, const GradientDual& b) {
    return a.value_ < b.value_;
  }
  friend bool operator>(const GradientDual& a, const GradientDual& b) {
    return a.value_ > b.value_;
  }
  friend bool operator<=(const GradientDual& a, const GradientDual& b) {
    return a.value_ <= b.value_;
  }
  friend bool operator>=(const GradientDual& a, const GradientDual& b) {
    return a.value_ >= b.value_;
  }
  friend bool operator==(const GradientDual& a, const GradientDual& b) {
    return a.value_ == b.value_;
  }
  friend bool operator!=(const GradientDual& a, const GradientDual& b) {
    return a.value_ != b.value_;
  }

  friend GradientDual sin(const GradientDual& a) {
    using std::cos;
    using std::sin;
    return a.apply(sin(a.value_), cos(a.value_));
  }
  friend GradientDual cos(const GradientDual& a) {
    using std::cos;
    using std::sin;
    return a.apply(cos(a.value_), -sin(a.value_));
  }
  friend GradientDual tan(const GradientDual& a) {
    using std::tan;
    const S t = tan(a.value_);
    return a.apply(t, one() + t * t);
  }
  friend GradientDual exp(const GradientDual& a) {
    using std::exp;
    const S e = exp(a.value_);
    return a.apply(e, e);
  }
  friend GradientDual log(const GradientDual& a) {
    using std::log;
    return a.apply(log(a.value_), one() / a.value_);
  }
  friend GradientDual sqrt(const GradientDual& a) {
    using std::sqrt;
    const S r = sqrt(a.value_);
    return a.apply(r, Constant<S>::of(0.5) / r);
  }
  friend GradientDual tanh(const GradientDual& a) {
    using std::tanh;
    const S t = tanh(a.value_);
    return a.apply(t, one() - t * t);
  }
  friend GradientDual atan(const GradientDual& a) {
    using std::atan;
    return a.apply(atan(a.value_), one() / (one() + a.value_ * a.value_));
  }
  friend GradientDual abs(const GradientDual& a) {
    return a.value_ < Constant<S>::of(0.0) ? -a : a;
  }
  friend GradientDual pow(const GradientDual& a, double exponent) {
    using std::pow;
    return a.apply(pow(a.value_, exponent), exponent * pow(a.value_, exponent - 1.0));
  }

 private:
  S value_;
  Vector gradient_;
};

}  // namespace fesd
