// What a warm start needs (scene/warm_start.cpp): each difference of structure or NLP size named,
// no warm start from a solve that did not solve its NLP, and the ladder's starting rung.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "fesd_trajopt/scene/warm_start.h"

namespace {

fesd::PlanStructure structure() {
  fesd::PlanStructure s;
  s.moving_bodies = {"joint shoulder", "puck (radius 0.3, passive)"};
  s.modelled_pairs = {"hand/sphere_0/puck"};
  s.horizon = 2.0;
  s.intervals = 8;
  s.interval_elements.assign(8, 2);
  s.stages = 2;
  return s;
}

const fesd::NlpSizes kSizes{1200, 1000, 64};

std::string refusal(const fesd::PlanStructure& previous, const fesd::PlanStructure& now,
                    const fesd::NlpSizes& now_sizes = kSizes) {
  return fesd::warmStartRefusal(true, kSizes.variables, kSizes, previous, now_sizes, now);
}

TEST(WarmStart, AStructureNamesItsBodiesAndTakesTheGrid) {
  EXPECT_EQ(fesd::movingBodyName({"puck", 0.3, Eigen::Vector2d::Zero(), false}),
            "puck (radius 0.3, passive)");
  EXPECT_EQ(fesd::movingBodyName({"pusher", 1.0, Eigen::Vector2d::Zero(), true}),
            "pusher (radius 1, actuated)");
  fesd::DiscretizationOptions grid;
  grid.num_elements = 2;
  grid.num_stages = 2;
  const fesd::PlanStructure built =
      fesd::planStructure(structure().moving_bodies, structure().modelled_pairs, 2.0, 8, grid);
  EXPECT_EQ(fesd::warmStartMismatch(built, structure()), "");
  grid.switch_detection = false;
  EXPECT_FALSE(fesd::planStructure({}, {}, 2.0, 8, grid).switch_detection);
}

TEST(WarmStart, TheSameStructureAndSizesFit) {
  EXPECT_EQ(refusal(structure(), structure()), "");
}

TEST(WarmStart, EachDifferenceIsNamedWithBothValues) {
  fesd::PlanStructure now = structure();
  now.moving_bodies.pop_back();
  EXPECT_EQ(refusal(structure(), now),
            "the moving bodies differ: [joint shoulder, puck (radius 0.3, passive)] -> [joint "
            "shoulder]");
  now = structure();
  now.modelled_pairs.push_back("hand/sphere_1/puck");
  EXPECT_EQ(refusal(structure(), now),
            "the modelled contact pairs differ: [hand/sphere_0/puck] -> [hand/sphere_0/puck, "
            "hand/sphere_1/puck]");
  now = structure();
  now.horizon = 3.0;
  EXPECT_EQ(refusal(structure(), now), "the horizons differ: 2 -> 3");
  now = structure();
  now.stages = 3;
  EXPECT_EQ(refusal(structure(), now),
            "the discretisations differ: 8 intervals x 2 elements, n_s = 2, FESD -> 8 intervals "
            "x 2 elements, n_s = 3, FESD");
  EXPECT_EQ(refusal(structure(), structure(), {1201, 1000, 64}),
            "the NLP sizes differ: 1200 variables, 1000 constraints -> 1201 variables, 1000 "
            "constraints");
}

TEST(WarmStart, OnlyASolutionOfItsNlpWarmStarts) {
  EXPECT_EQ(
      fesd::warmStartRefusal(false, kSizes.variables, kSizes, structure(), kSizes, structure()),
      "no previous solution");
  // A point of another NLP (e.g. an interrupted fixed-grid stage) is no start either.
  EXPECT_EQ(fesd::warmStartRefusal(true, 900, kSizes, structure(), kSizes, structure()),
            "no previous solution");
}

TEST(WarmStart, ALazyFirstRoundTakesThePreviousPairsOnlyWhenAllAreCandidates) {
  const std::vector<std::string> candidates{"a/b", "a/c", "b/c"};
  EXPECT_EQ(fesd::previousPairsAmong(candidates, {"b/c", "a/b"}),
            (std::vector<bool>{true, false, true}));
  EXPECT_EQ(fesd::previousPairsAmong(candidates, {}), (std::vector<bool>{false, false, false}));
  EXPECT_TRUE(fesd::previousPairsAmong(candidates, {"a/b", "c/d"}).empty());  // c/d out of reach
}

TEST(WarmStart, ReplanningStartsOnThePreviousPlansRungWhenItIsFiner) {
  fesd::DiscretizationOptions grid;
  grid.num_stages = 2;
  grid.num_elements = 2;
  fesd::PlanStructure previous = structure();
  previous.stages = 4;
  previous.interval_elements = {3, 3, 3, 6, 6, 3, 3, 3};  // a ladder refined intervals 3 and 4
  fesd::startOnPreviousRung(previous, 8, 2.0, grid);
  EXPECT_EQ(grid.num_stages, 4);
  EXPECT_EQ(grid.interval_elements, previous.interval_elements);
  fesd::DiscretizationOptions finer;
  finer.num_elements = 5;  // the request asks for more than the previous plan had
  fesd::startOnPreviousRung(previous, 8, 2.0, finer);
  EXPECT_EQ(finer.num_elements, 5);
  EXPECT_TRUE(finer.interval_elements.empty());
  EXPECT_EQ(finer.num_stages, fesd::DiscretizationOptions{}.num_stages);
  fesd::DiscretizationOptions more_intervals;
  fesd::startOnPreviousRung(previous, 10, 2.5, more_intervals);
  EXPECT_TRUE(more_intervals.interval_elements.empty());
  // Three intervals of 0.25 s executed: the rest of the previous grid.
  fesd::DiscretizationOptions rest;
  rest.num_elements = 2;
  fesd::startOnPreviousRung(previous, 5, 1.25, rest);
  EXPECT_EQ(rest.interval_elements, (std::vector<int>{6, 6, 3, 3, 3}));
  EXPECT_EQ(rest.num_stages, 4);
  fesd::DiscretizationOptions other_length;
  fesd::startOnPreviousRung(previous, 5, 1.0, other_length);
  EXPECT_TRUE(other_length.interval_elements.empty());
  fesd::DiscretizationOptions standard;
  standard.switch_detection = false;
  fesd::startOnPreviousRung(previous, 8, 2.0, standard);
  EXPECT_EQ(standard.num_stages, fesd::DiscretizationOptions{}.num_stages);
}

}  // namespace
