// SmoothFunction's shared pieces (function/smooth_function.cpp): dense patterns, and the copies
// made for another thread, state shared by several functions copied once.
#include <memory>

#include <gtest/gtest.h>

#include "fesd_trajopt/function/smooth_function.h"

namespace {

TEST(SparsityPattern, DenseHoldsEveryEntryOrTheLowerTriangleRowByRow) {
  const fesd::SparsityPattern full = fesd::SparsityPattern::dense(2, 3);
  EXPECT_EQ(full.rows, (std::vector<int>{0, 0, 0, 1, 1, 1}));
  EXPECT_EQ(full.cols, (std::vector<int>{0, 1, 2, 0, 1, 2}));
  const fesd::SparsityPattern lower = fesd::SparsityPattern::dense(3, 3, true);
  EXPECT_EQ(lower.rows, (std::vector<int>{0, 1, 1, 2, 2, 2}));
  EXPECT_EQ(lower.cols, (std::vector<int>{0, 0, 1, 0, 1, 2}));
}

/// y = z0 + cache, the cache shared with its siblings (as pair functions share kinematics).
struct Cache {
  double value = 0.0;
};
class Cached : public fesd::SmoothFunction {
 public:
  explicit Cached(std::shared_ptr<const Cache> cache) : cache_(std::move(cache)) {
    jacobian_.add(0, 0);
  }
  int inputSize() const override { return 1; }
  int outputSize() const override { return 1; }
  void evaluate(const double* z, double* y) const override { y[0] = z[0] + cache_->value; }
  const fesd::SparsityPattern& jacobianPattern() const override { return jacobian_; }
  void evaluateJacobian(const double*, double* values) const override { values[0] = 1.0; }
  const fesd::SparsityPattern& hessianPattern() const override { return hessian_; }
  void evaluateHessian(const double*, const double*, double*) const override {}
  std::shared_ptr<const fesd::SmoothFunction> threadCopy(
      fesd::ThreadCopies& copies) const override {
    ++copies_made;
    return std::make_shared<Cached>(
        copies.of<Cache>(cache_.get(), [&] { return std::make_shared<const Cache>(*cache_); }));
  }
  const Cache* cache() const { return cache_.get(); }
  mutable int copies_made = 0;

 private:
  std::shared_ptr<const Cache> cache_;
  fesd::SparsityPattern jacobian_, hessian_;
};

/// y = 2 z0: no state, shared as it is.
class Stateless : public Cached {
 public:
  Stateless() : Cached(std::make_shared<const Cache>()) {}
  std::shared_ptr<const fesd::SmoothFunction> threadCopy(fesd::ThreadCopies&) const override {
    return nullptr;
  }
};

TEST(ThreadCopies, FunctionsSharingStateShareOneCopyOfItAndEachIsCopiedOnce) {
  const auto cache = std::make_shared<const Cache>(Cache{0.5});
  const auto first = std::make_shared<Cached>(cache), second = std::make_shared<Cached>(cache);
  fesd::ThreadCopies copies;
  const auto first_copy = copies.function(first), second_copy = copies.function(second);
  EXPECT_EQ(copies.function(first), first_copy);  // asked again: the same copy
  EXPECT_EQ(first->copies_made, 1);
  ASSERT_NE(first_copy, first);
  const auto& a = dynamic_cast<const Cached&>(*first_copy);
  const auto& b = dynamic_cast<const Cached&>(*second_copy);
  EXPECT_NE(a.cache(), cache.get());
  EXPECT_EQ(a.cache(), b.cache());
  double y = 0.0, z = 2.0;
  a.evaluate(&z, &y);
  EXPECT_EQ(y, 2.5);
}

TEST(ThreadCopies, AFunctionWithoutStateIsSharedAsItIs) {
  const auto stateless = std::make_shared<Stateless>();
  fesd::ThreadCopies copies;
  EXPECT_EQ(copies.function(stateless), stateless);
}

}  // namespace
