// Paths round discs (planning/paths_around.cpp): the straight segment when it is clear, the
// shortest way round a disc against the exact geodesic, turning points that keep their corner
// distance, discs that hold an end (kept out of as far as the end lies), a region that rules
// out one side, no way round at all, and the polyline helpers.
#include <cmath>

#include <gtest/gtest.h>

#include "fesd_trajopt/planning/paths_around.h"

namespace {

double distanceToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                         const Eigen::Vector2d& b) {
  const double s = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
  return (a + s * (b - a) - p).norm();
}

/// Every piece of the path keeps `distance` from the disc's centre.
void expectClear(const std::vector<Eigen::Vector2d>& path, const fesd::KeepOut& disc) {
  for (size_t k = 1; k < path.size(); ++k) {
    EXPECT_GE(distanceToSegment(disc.centre, path[k - 1], path[k]), disc.distance * (1 - 1e-9))
        << "piece " << k;
  }
}

fesd::PathQuery between(const Eigen::Vector2d& from, const Eigen::Vector2d& to,
                        std::vector<fesd::KeepOut> discs) {
  fesd::PathQuery query;
  query.from = from;
  query.to = to;
  query.keep_out = std::move(discs);
  return query;
}

double length(const std::vector<Eigen::Vector2d>& path) {
  return fesd::pathLength(std::vector<Eigen::VectorXd>(path.begin(), path.end()));
}

TEST(PathsAround, AClearSegmentIsTheWholePath) {
  fesd::PathQuery query = between(Eigen::Vector2d(-3, 0), Eigen::Vector2d(3, 0), {});
  query.keep_out.push_back({Eigen::Vector2d(0, 2), 1.0, 1.0});
  const std::vector<Eigen::Vector2d> path = fesd::pathAround(query);
  ASSERT_EQ(path.size(), 2u);
  EXPECT_EQ(path[0], query.from);
  EXPECT_EQ(path[1], query.to);
}

TEST(PathsAround, ADiscInTheWayIsGoneRoundAboutAsShortAsTheGeodesic) {
  const fesd::KeepOut disc{Eigen::Vector2d(0, 0), 1.0, 1.0};
  const fesd::PathQuery query = between(Eigen::Vector2d(-3, 0), Eigen::Vector2d(3, 0), {disc});
  const std::vector<Eigen::Vector2d> path = fesd::pathAround(query);
  ASSERT_GT(path.size(), 2u);
  EXPECT_EQ(path.front(), query.from);
  EXPECT_EQ(path.back(), query.to);
  expectClear(path, disc);
  // Two tangents of sqrt(8) and the arc between their touching points on the unit circle.
  const double geodesic = 2.0 * std::sqrt(8.0) + (M_PI - 2.0 * std::acos(1.0 / 3.0));
  EXPECT_GE(length(path), geodesic);
  EXPECT_LE(length(path), 1.02 * geodesic);
}

TEST(PathsAround, TurningPointsKeepTheCornerDistance) {
  const fesd::KeepOut disc{Eigen::Vector2d(0, 0), 1.0, 2.0};
  const fesd::PathQuery query = between(Eigen::Vector2d(-5, 0), Eigen::Vector2d(5, 0), {disc});
  const std::vector<Eigen::Vector2d> path = fesd::pathAround(query);
  ASSERT_GT(path.size(), 2u);
  for (size_t k = 1; k + 1 < path.size(); ++k) EXPECT_GE(path[k].norm(), 2.0);
}

TEST(PathsAround, ADiscHoldingAnEndIsKeptOutOfAsFarAsTheEndLies) {
  // The goal 0.5 inside a disc of distance 1.5: nothing on the way comes nearer than 1.
  const fesd::KeepOut disc{Eigen::Vector2d(4, 0), 1.5, 1.5};
  const fesd::PathQuery query = between(Eigen::Vector2d(6, 0.5), Eigen::Vector2d(3, 0), {disc});
  const std::vector<Eigen::Vector2d> path = fesd::pathAround(query);
  ASSERT_GT(path.size(), 2u);
  EXPECT_EQ(path.back(), query.to);
  expectClear(path, {disc.centre, 1.0, 1.0});
  // A goal exactly at the keep-out distance (a pusher arriving in contact) is outside it.
  const fesd::KeepOut touched{Eigen::Vector2d(4, 0), 1.0, 1.5};
  const fesd::PathQuery arriving = between(Eigen::Vector2d(5, 0), Eigen::Vector2d(3, 0), {touched});
  const std::vector<Eigen::Vector2d> round = fesd::pathAround(arriving);
  ASSERT_GT(round.size(), 2u);
  expectClear(round, touched);
  EXPECT_EQ(round.back(), arriving.to);
  // A goal at the very centre of a disc (a body shoved off it): the disc is no obstacle.
  const fesd::PathQuery onto = between(Eigen::Vector2d(0, 0), Eigen::Vector2d(4, 0), {touched});
  EXPECT_EQ(fesd::pathAround(onto).size(), 2u);
}

TEST(PathsAround, TheAllowedRegionDecidesTheSide) {
  const fesd::KeepOut disc{Eigen::Vector2d(0, 0.1), 1.0, 1.0};  // the way above is shorter
  fesd::PathQuery query = between(Eigen::Vector2d(-3, 0), Eigen::Vector2d(3, 0), {disc});
  const std::vector<Eigen::Vector2d> free = fesd::pathAround(query);
  ASSERT_GT(free.size(), 2u);
  EXPECT_LT(free[1].y(), 0.0);  // below: the disc sits above the line
  query.allowed = [](const Eigen::Vector2d& p) { return p.y() >= 0.0; };
  const std::vector<Eigen::Vector2d> above = fesd::pathAround(query);
  ASSERT_GT(above.size(), 2u);
  for (const Eigen::Vector2d& p : above) EXPECT_GE(p.y(), 0.0);
  expectClear(above, disc);
}

TEST(PathsAround, WithoutAWayRoundThePathIsStraight) {
  // The goal inside a ring of discs that overlap.
  fesd::PathQuery query = between(Eigen::Vector2d(-6, 0), Eigen::Vector2d(0, 0), {});
  for (int k = 0; k < 12; ++k) {
    const double angle = 2.0 * M_PI * k / 12;
    query.keep_out.push_back({3.0 * Eigen::Vector2d(std::cos(angle), std::sin(angle)), 1.0, 1.0});
  }
  EXPECT_EQ(fesd::pathAround(query).size(), 2u);
}

TEST(PathsAround, ALegCostPrefersFewerPieces) {
  // Two discs side by side across the line: round both at once (2 pieces) or between them.
  const fesd::KeepOut upper{Eigen::Vector2d(0, 1.05), 1.0, 1.0};
  const fesd::KeepOut lower{Eigen::Vector2d(0, -1.05), 1.0, 1.0};
  fesd::PathQuery query = between(Eigen::Vector2d(-4, 0), Eigen::Vector2d(4, 0), {upper, lower});
  const size_t pieces_free = fesd::pathAround(query).size() - 1;
  query.leg_cost = 10.0;
  const std::vector<Eigen::Vector2d> path = fesd::pathAround(query);
  EXPECT_LE(path.size() - 1, pieces_free);
  EXPECT_LE(path.size() - 1, 3u);
  expectClear(path, upper);
  expectClear(path, lower);
}

TEST(PathsAround, PiecesMustBePassableInTheirDirectionOfTravel) {
  // Nothing in the way, but below y = 1 a piece must head at least as much up as sideways: the
  // way leads through the waypoint (1, 2), not straight nor through (5, 0.5).
  fesd::PathQuery query = between(Eigen::Vector2d(0, 0), Eigen::Vector2d(3, 0), {});
  query.passable = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return b.y() - a.y() >= std::fabs(b.x() - a.x()) || a.y() > 1.0;  // up first, then anything
  };
  EXPECT_EQ(fesd::pathAround(query).size(), 2u);  // no waypoint: the straight fallback
  query.waypoints = {Eigen::Vector2d(1, 2), Eigen::Vector2d(5, 0.5)};
  const std::vector<Eigen::Vector2d> path = fesd::pathAround(query);
  ASSERT_EQ(path.size(), 3u);
  EXPECT_EQ(path[1], Eigen::Vector2d(1, 2));
}

TEST(PathsAround, ARoundedCornerIsAnArcWithContinuousTangents) {
  // A right angle at (2, 0) rounded with radius 0.5: length 4 - 2 * 0.5 + pi / 4.
  const fesd::RoundedPath path(
      {Eigen::Vector2d(0, 0), Eigen::Vector2d(2, 0), Eigen::Vector2d(2, 2)}, 0.5);
  EXPECT_NEAR(path.length(), 3.0 + M_PI / 4.0, 1e-12);
  EXPECT_LT((path.at(1.0) - Eigen::Vector2d(1, 0)).norm(), 1e-12);
  EXPECT_LT((path.at(path.length()) - Eigen::Vector2d(2, 2)).norm(), 1e-12);
  // The arc's middle lies 0.5 from the centre (1.5, 0.5), on the diagonal.
  const Eigen::Vector2d middle = path.at(1.5 + M_PI / 8.0);
  EXPECT_NEAR((middle - Eigen::Vector2d(1.5, 0.5)).norm(), 0.5, 1e-12);
  EXPECT_NEAR(middle.x() - 1.5, 0.5 / std::sqrt(2.0), 1e-12);
  for (double s = 0.01; s < path.length(); s += 0.01) {
    EXPECT_LT((path.tangent(s) - path.tangent(s - 0.01)).norm(), 0.021) << "s = " << s;
    const Eigen::Vector2d slope = (path.at(s + 1e-6) - path.at(s - 1e-6)) / 2e-6;
    EXPECT_LT((slope - path.tangent(s)).norm(), 1e-6) << "s = " << s;
  }
  // Pieces too short for the radius get a smaller arc: the corners' arcs do not overlap.
  const fesd::RoundedPath tight({Eigen::Vector2d(0, 0), Eigen::Vector2d(0.2, 0),
                                 Eigen::Vector2d(0.2, 0.2), Eigen::Vector2d(0, 0.2)},
                                1.0);
  EXPECT_NEAR(tight.length(), 0.2 + 0.1 * M_PI, 1e-12);  // two arcs of radius 0.1
}

TEST(PathsAround, PointsAlongAPolylineGoByArcLength) {
  const std::vector<Eigen::VectorXd> path{Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0),
                                          Eigen::Vector2d(1, 3)};
  EXPECT_DOUBLE_EQ(fesd::pathLength(path), 4.0);
  EXPECT_LT((fesd::pointAlong(path, 0.25) - Eigen::Vector2d(1, 0)).norm(), 1e-15);
  EXPECT_LT((fesd::pointAlong(path, 0.5) - Eigen::Vector2d(1, 1)).norm(), 1e-15);
  EXPECT_LT((fesd::pointAlong(path, 2.0) - Eigen::Vector2d(1, 3)).norm(), 1e-15);
  EXPECT_LT((fesd::pointAlong(path, -1.0) - Eigen::Vector2d(0, 0)).norm(), 1e-15);
}

}  // namespace
