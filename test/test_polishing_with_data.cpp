// Active-set polishing (NlpAssembly::fixActiveSet) when a complementarity side holds fixed data,
// as c and lambda at a simulation step's start point do: such a side cannot be made zero.
#include <gtest/gtest.h>

#include "fesd_trajopt/nlp/nlp_assembly.h"

namespace {

constexpr double kInf = fesd::NlpAssembly::kInfinity;

/// (d + a) _|_ b with d fixed data, a and b free and nonnegative; no objective needed.
struct PairWithData {
  fesd::NlpAssembly nlp;
  int data, a, b;
  explicit PairWithData(double data_value) {
    data = nlp.addVariables(1, data_value, data_value, data_value);
    a = nlp.addVariables(1, 0.0, kInf);
    b = nlp.addVariables(1, 0.0, kInf);
    nlp.addComplementarity({{data, 1.0}, {a, 1.0}}, {{b, 1.0}});
    nlp.finalize();
  }
};

TEST(PolishingWithData, TheSideWithNonzeroDataStaysFreeEvenWhenSmaller) {
  PairWithData pair(0.5);
  const double x[] = {0.5, 0.0, 0.7};  // left 0.5 < right 0.7
  ASSERT_TRUE(pair.nlp.fixActiveSet(x));
  EXPECT_EQ(pair.nlp.variableUpper(pair.b), 0.0);   // the right side is the zero side
  EXPECT_EQ(pair.nlp.variableUpper(pair.a), kInf);  // the left side stays free
  pair.nlp.releaseActiveSet();
  EXPECT_EQ(pair.nlp.variableUpper(pair.b), kInf);
}

TEST(PolishingWithData, NegligibleDataCountsAsZero) {
  PairWithData pair(1e-12);  // e.g. c(x) of a start point on a curved boundary
  const double x[] = {1e-12, 0.0, 0.7};
  ASSERT_TRUE(pair.nlp.fixActiveSet(x));
  EXPECT_EQ(pair.nlp.variableUpper(pair.a), 0.0);
  EXPECT_EQ(pair.nlp.variableUpper(pair.b), kInf);
}

TEST(PolishingWithData, RefusedWhenBothSidesHoldNonzeroData) {
  fesd::NlpAssembly nlp;
  const int c0 = nlp.addVariables(1, 0.2, 0.2, 0.2);
  const int lambda0 = nlp.addVariables(1, 0.3, 0.3, 0.3);
  const int a = nlp.addVariables(1, 0.0, kInf);
  nlp.addComplementarity({{c0, 1.0}, {a, 1.0}}, {{lambda0, 1.0}});
  nlp.finalize();
  const double x[] = {0.2, 0.3, 0.0};
  EXPECT_FALSE(nlp.fixActiveSet(x));
  EXPECT_EQ(nlp.variableUpper(a), kInf);  // nothing changed
}

}  // namespace
