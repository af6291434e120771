// Fuzzing request validation and scene building with seeded random inputs: nothing crashes,
// throws or hangs; every defect is refused with a message that names it; every accepted task
// builds an OCP and an NLP that evaluates to finite numbers at its guess.
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include <console_bridge/console.h>
#include <gtest/gtest.h>

#include "fesd_trajopt/discretization/pds_discretization.h"
#include "fesd_trajopt/scene/moving_part.h"
#include "fesd_trajopt/scene/robot_from_urdf.h"
#include "fesd_trajopt/scene/scene_task.h"
#include "fesd_trajopt/scene/urdf_scene.h"

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

class Fuzzer {
 public:
  explicit Fuzzer(unsigned seed) : random_(seed) {}

  int integer(int low, int high) { return std::uniform_int_distribution<int>(low, high)(random_); }
  bool chance(double p) { return std::bernoulli_distribution(p)(random_); }
  double uniform(double low, double high) {
    return std::uniform_real_distribution<double>(low, high)(random_);
  }
  /// A number that is ordinary most of the time, else one of the troublesome ones.
  double number(double low, double high) {
    static const double nasty[] = {0.0,    -0.0, -1.0,  1e-300, -1e-300, 1e300,
                                   -1e300, kInf, -kInf, kNaN,   1e7,     5e-324};
    return chance(0.8) ? uniform(low, high) : nasty[integer(0, 11)];
  }
  Eigen::VectorXd vector(int size, double low, double high) {
    Eigen::VectorXd v(size);
    for (int i = 0; i < size; ++i) v(i) = number(low, high);
    return v;
  }
  /// Mostly the right size, sometimes one off or empty.
  int size(int right) {
    if (chance(0.85)) return right;
    return std::max(0, right + integer(-2, 1));
  }

  /// Anything at all: most of these are invalid, which is the point.
  fesd::SceneTask garbageTask() {
    const int dim = chance(0.9) ? integer(2, 3) : integer(0, 4);
    fesd::SceneTask task;
    task.scene = fesd::Scene(dim);
    const int bodies = chance(0.95) ? integer(0, 5) : 31;
    for (int b = 0; b < bodies; ++b) {
      task.scene.bodies().push_back({"b" + std::to_string(integer(0, bodies)), number(0.1, 1.0),
                                     vector(size(dim), -20, 20), chance(0.5)});
      fesd::BodyTask t;
      t.max_speed = number(0.0, 10.0);
      if (chance(0.5)) t.target = vector(size(dim), -20, 20);
      t.target_weight = chance(0.5) ? number(0.0, 10.0) : 0.0;
      if (chance(0.3)) t.workspace_lower = vector(size(dim), -30, 0);
      if (chance(0.3)) t.workspace_upper = vector(size(dim), 0, 30);
      task.bodies.push_back(t);
    }
    if (chance(0.1)) task.bodies.resize(integer(0, bodies + 1));
    for (int o = integer(0, 3); o > 0; --o) {
      task.scene.obstacles().push_back(
          {"o" + std::to_string(o), number(0.1, 2.0), vector(size(dim), -20, 20)});
    }
    for (int w = integer(0, 2); w > 0; --w) {
      Eigen::VectorXd normal = vector(size(dim), -1, 1);
      if (chance(0.8) && normal.norm() > 0 && std::isfinite(normal.norm())) normal.normalize();
      task.scene.walls().push_back({"w" + std::to_string(w), normal, number(-40, -25)});
    }
    task.horizon = number(0.1, 5.0);
    task.num_intervals = chance(0.9) ? integer(1, 6) : integer(-5, 100000);
    task.control_weight = number(0.0, 1.0);
    if (chance(0.2)) {
      task.allowed_pairs.push_back(
          {integer(-1, bodies), fesd::ContactPair::Kind(integer(0, 2)), integer(-1, 3)});
    }
    return task;
  }

  /// A valid task: bodies on a grid 3 apart (radii <= 1), one actuated, bounds around starts.
  fesd::SceneTask validTask() {
    const int dim = integer(2, 3);
    fesd::SceneTask task;
    task.scene = fesd::Scene(dim);
    const int bodies = integer(1, 6);
    for (int b = 0; b < bodies; ++b) {
      Eigen::VectorXd p = Eigen::VectorXd::Zero(dim);
      p(0) = 3.0 * (b % 3);
      p(1) = 3.0 * (b / 3);
      task.scene.bodies().push_back({"body" + std::to_string(b), uniform(0.2, 1.0), p, b == 0});
      fesd::BodyTask t;
      t.max_speed = uniform(0.0, 3.0);
      if (chance(0.5)) {
        t.target = p + Eigen::VectorXd::Constant(dim, uniform(-0.5, 0.5));
        t.target_weight = uniform(0.1, 10.0);
      }
      if (chance(0.3)) t.workspace_lower = p.array() - uniform(1.0, 5.0);
      if (chance(0.3)) t.workspace_upper = p.array() + uniform(1.0, 5.0);
      task.bodies.push_back(t);
    }
    if (chance(0.5)) {
      task.scene.obstacles().push_back(
          {"post", uniform(0.1, 0.5), Eigen::VectorXd::Constant(dim, -3.0)});
    }
    if (chance(0.5)) {
      Eigen::VectorXd normal = Eigen::VectorXd::Zero(dim);
      normal(1) = 1.0;
      task.scene.walls().push_back({"floor", normal, -2.0});
    }
    task.horizon = uniform(0.5, 3.0);
    task.num_intervals = integer(1, 4);
    return task;
  }

 private:
  std::mt19937 random_;
};

/// One defect of a valid task and the word its message must contain.
struct Defect {
  const char* keyword;
  void (*apply)(fesd::SceneTask&, Fuzzer&);
};

const Defect kDefects[] = {
    {"radius",
     [](fesd::SceneTask& t, Fuzzer& f) { t.scene.bodies()[0].radius = -f.uniform(0, 1); }},
    {"radius", [](fesd::SceneTask& t, Fuzzer&) { t.scene.bodies()[0].radius = kNaN; }},
    {"not finite", [](fesd::SceneTask& t, Fuzzer&) { t.scene.bodies()[0].position(1) = kInf; }},
    {"coordinates",
     [](fesd::SceneTask& t, Fuzzer&) { t.scene.bodies()[0].position.conservativeResize(1); }},
    {"coordinate limit",
     [](fesd::SceneTask& t, Fuzzer&) { t.scene.bodies()[0].position(0) = 1e9; }},
    {"horizon", [](fesd::SceneTask& t, Fuzzer& f) { t.horizon = -f.uniform(0, 1); }},
    {"horizon", [](fesd::SceneTask& t, Fuzzer&) { t.horizon = kNaN; }},
    {"intervals", [](fesd::SceneTask& t, Fuzzer& f) { t.num_intervals = -f.integer(0, 9); }},
    {"control weight", [](fesd::SceneTask& t, Fuzzer&) { t.control_weight = -1.0; }},
    {"speed bound", [](fesd::SceneTask& t, Fuzzer&) { t.bodies[0].max_speed = kNaN; }},
    {"target", [](fesd::SceneTask& t, Fuzzer&) { t.bodies[0].target = Eigen::VectorXd::Ones(4); }},
    {"no target",
     [](fesd::SceneTask& t, Fuzzer&) {
       t.bodies[0].target.resize(0);
       t.bodies[0].target_weight = 1.0;
     }},
    {"target weight", [](fesd::SceneTask& t, Fuzzer&) { t.bodies[0].target_weight = -kInf; }},
    {"NaN",
     [](fesd::SceneTask& t, Fuzzer&) {
       t.bodies[0].workspace_lower = Eigen::VectorXd::Constant(t.scene.dimension(), kNaN);
     }},
    {"contradictory",
     [](fesd::SceneTask& t, Fuzzer&) {
       t.bodies[0].workspace_lower = Eigen::VectorXd::Constant(t.scene.dimension(), 1.0);
       t.bodies[0].workspace_upper = Eigen::VectorXd::Constant(t.scene.dimension(), -1.0);
     }},
    {"outside its workspace",
     [](fesd::SceneTask& t, Fuzzer&) {
       t.bodies[0].workspace_lower = t.scene.bodies()[0].position.array() + 0.5;
       t.bodies[0].workspace_upper.resize(0);
     }},
    {"actuated", [](fesd::SceneTask& t, Fuzzer&) { t.scene.bodies()[0].actuated = false; }},
    {"overlap",
     [](fesd::SceneTask& t, Fuzzer&) {
       t.scene.obstacles().push_back({"inside", 0.1, t.scene.bodies()[0].position});
     }},
    {"unit normal",
     [](fesd::SceneTask& t, Fuzzer&) {
       t.scene.walls().push_back({"bad", Eigen::VectorXd::Zero(t.scene.dimension()), 0.0});
     }},
    {"named",
     [](fesd::SceneTask& t, Fuzzer&) {
       t.scene.bodies().push_back(t.scene.bodies()[0]);
       t.scene.bodies().back().position(0) -= 5.0;
       t.bodies.push_back(t.bodies[0]);
       t.bodies.back().workspace_lower.resize(0);
       t.bodies.back().workspace_upper.resize(0);
     }},
    {"too many bodies",
     [](fesd::SceneTask& t, Fuzzer&) {
       for (int b = 0; b < 30; ++b) {
         Eigen::VectorXd p = Eigen::VectorXd::Constant(t.scene.dimension(), -100.0);
         p(0) -= 3.0 * b;
         t.scene.bodies().push_back({"extra" + std::to_string(b), 0.5, p, false});
         t.bodies.emplace_back();
       }
     }},
    {"one body task per body", [](fesd::SceneTask& t, Fuzzer&) { t.bodies.emplace_back(); }},
    {"allowed contact pair",
     [](fesd::SceneTask& t, Fuzzer&) {
       t.allowed_pairs.push_back({0, fesd::ContactPair::Kind::kObstacle, 7});
     }},
};

/// Builds everything a solve would from a valid task and checks the NLP at its guess.
void buildAndEvaluate(const fesd::SceneTask& task) {
  const std::string infeasible = fesd::infeasibility(task);
  const std::vector<fesd::PairDecision> decisions = fesd::decidePairs(task);
  ASSERT_EQ(decisions.size(), task.scene.allPairs().size());
  const fesd::MovingPart part = fesd::movingPart(task, decisions);
  const fesd::OcpDefinition ocp = fesd::buildOcp(part.task, part.modelled);
  fesd::DiscretizationOptions options;
  options.num_elements = 2;
  fesd::PdsDiscretization discretization(ocp, options);
  const fesd::NlpAssembly& nlp = discretization.nlp();
  const std::vector<double> guess = discretization.constantGuess();
  ASSERT_EQ(static_cast<int>(guess.size()), nlp.numVariables());
  EXPECT_TRUE(std::isfinite(nlp.objective(guess.data())));
  std::vector<double> g(nlp.numConstraints());
  nlp.constraints(guess.data(), g.data());
  for (double value : g) ASSERT_TRUE(std::isfinite(value));
  std::vector<double> jacobian(nlp.jacobianPattern().nonzeros());
  nlp.jacobian(guess.data(), jacobian.data());
  for (double value : jacobian) ASSERT_TRUE(std::isfinite(value));
}

TEST(RequestFuzz, GarbageTasksAreRefusedWithAMessageOrBuildAFiniteNlp) {
  Fuzzer fuzzer(20261122);
  int accepted = 0;
  for (int i = 0; i < 20000; ++i) {
    const fesd::SceneTask task = fuzzer.garbageTask();
    std::string message;
    ASSERT_NO_THROW(message = fesd::validateTask(task, fesd::TaskLimits{})) << "case " << i;
    if (!message.empty()) {
      EXPECT_LT(message.size(), 200u) << message;
      continue;
    }
    ++accepted;
    ASSERT_NO_FATAL_FAILURE(buildAndEvaluate(task)) << "case " << i;
  }
  EXPECT_GT(accepted, 50);  // the valid path is exercised too
  RecordProperty("garbage_accepted", accepted);
}

TEST(RequestFuzz, EveryDefectOfAValidTaskIsRefusedByName) {
  Fuzzer fuzzer(7);
  for (int i = 0; i < 2000; ++i) {
    fesd::SceneTask task = fuzzer.validTask();
    ASSERT_EQ(fesd::validateTask(task, fesd::TaskLimits{}), "") << "case " << i;
    if (i % 10 == 0) {
      ASSERT_NO_FATAL_FAILURE(buildAndEvaluate(task)) << "case " << i;
    }
    const Defect& defect = kDefects[fuzzer.integer(0, std::size(kDefects) - 1)];
    defect.apply(task, fuzzer);
    const std::string message = fesd::validateTask(task, fesd::TaskLimits{});
    EXPECT_NE(message.find(defect.keyword), std::string::npos)
        << "case " << i << ": expected '" << defect.keyword << "', got '" << message << "'";
  }
}

/// `xml` with 1 to 4 random edits (deletions, insertions, replacements) of XML and number
/// characters.
std::string mutatedXml(std::string xml, Fuzzer& fuzzer) {
  const std::string alphabet = "<>/=\" -.0123456789eEnaifNx\n";
  for (int edits = fuzzer.integer(1, 4); edits > 0; --edits) {
    const size_t at = fuzzer.integer(0, static_cast<int>(xml.size()) - 1);
    switch (fuzzer.integer(0, 2)) {
      case 0:
        xml.erase(at, fuzzer.integer(1, 8));
        break;
      case 1:
        xml.insert(at, 1, alphabet[fuzzer.integer(0, alphabet.size() - 1)]);
        break;
      default:
        xml[at] = alphabet[fuzzer.integer(0, alphabet.size() - 1)];
    }
  }
  return xml;
}

TEST(RequestFuzz, MutatedUrdfNeverCrashesTheSceneReader) {
  const std::string urdf = R"(<robot name="r"><link name="world"/>
    <link name="a"><collision><geometry><sphere radius="0.5"/></geometry></collision></link>
    <joint name="ja" type="floating"><parent link="world"/><child link="a"/>
      <origin xyz="1 2 0"/></joint>
    <link name="post"><collision><geometry><cylinder radius="0.3" length="1"/></geometry>
      </collision></link>
    <joint name="jp" type="fixed"><parent link="world"/><child link="post"/>
      <origin xyz="0 4 0" rpy="0 0 1"/></joint></robot>)";
  ASSERT_EQ(fesd::sceneFromUrdf(urdf, true).error, "");
  // urdfdom logs every parse error; thousands of them would bury the test output.
  console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_NONE);
  Fuzzer fuzzer(99);
  int readable = 0;
  for (int i = 0; i < 3000; ++i) {
    const std::string mutated = mutatedXml(urdf, fuzzer);
    fesd::UrdfScene scene;
    ASSERT_NO_THROW(scene = fesd::sceneFromUrdf(mutated, fuzzer.chance(0.5))) << mutated;
    if (!scene.error.empty()) continue;
    ++readable;
    // What the reader accepts, validation judges: a message or a task that builds.
    fesd::SceneTask task;
    task.scene = scene.scene;
    task.bodies.resize(scene.scene.bodies().size());
    if (!task.scene.bodies().empty()) task.scene.bodies()[0].actuated = true;
    task.num_intervals = 2;
    if (fesd::validateTask(task, fesd::TaskLimits{}).empty()) {
      ASSERT_NO_FATAL_FAILURE(buildAndEvaluate(task)) << mutated;
    }
  }
  RecordProperty("urdf_readable", readable);
}

TEST(RequestFuzz, MutatedRobotUrdfNeverCrashesTheRobotReader) {
  // A revolute arm of two spheres and a puck of two spheres on a floating joint of a fixed,
  // offset table: every path of robotForScene.
  const std::string urdf = R"(<robot name="r"><link name="world"/>
    <link name="arm"><collision><origin xyz="0.2 0 0"/><geometry><sphere radius="0.1"/></geometry>
      </collision><collision><origin xyz="0.4 0 0"/><geometry><sphere radius="0.1"/></geometry>
      </collision></link>
    <joint name="hinge" type="revolute"><parent link="world"/><child link="arm"/>
      <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
    <link name="table"/>
    <joint name="stand" type="fixed"><parent link="world"/><child link="table"/>
      <origin xyz="0.5 0 0" rpy="0 0 0.3"/></joint>
    <link name="puck"><collision><geometry><sphere radius="0.05"/></geometry></collision>
      <collision><origin xyz="0.1 0 0"/><geometry><sphere radius="0.05"/></geometry></collision>
    </link>
    <joint name="loose" type="floating"><parent link="table"/><child link="puck"/>
      <origin xyz="0.2 0.3 0"/></joint></robot>)";
  const fesd::RobotForScene intact = fesd::robotForScene(urdf, fesd::PlanarChoice::kInferred);
  ASSERT_EQ(intact.error, "");
  ASSERT_EQ(intact.free_bodies.size(), 1u);
  ASSERT_EQ(intact.free_bodies[0].spheres.size(), 2u);
  console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_NONE);
  Fuzzer fuzzer(7);
  int readable = 0;
  for (int i = 0; i < 2000; ++i) {
    const std::string mutated = mutatedXml(urdf, fuzzer);
    const fesd::PlanarChoice choice =
        fuzzer.chance(0.5) ? fesd::PlanarChoice::kInferred : fesd::PlanarChoice::kSpatial;
    fesd::RobotForScene read;
    ASSERT_NO_THROW(read = fesd::robotForScene(mutated, choice)) << mutated;
    if (!read.error.empty()) continue;
    ++readable;
    // What the reader accepts, the task judges: a message, or pairs with finite start gaps.
    fesd::Scene discs(read.dimension);
    discs.bodies() = read.free_bodies;
    const fesd::SceneTask task = fesd::taskOn(
        fesd::robotInScene(read.robot, Eigen::VectorXd::Zero(read.robot->numCoordinates()), discs));
    if (!fesd::validateTask(task, fesd::TaskLimits{}).empty()) continue;
    for (const fesd::PairDecision& decision : fesd::decidePairs(task)) {
      ASSERT_TRUE(std::isfinite(task.scene.pairGap(decision.pair, task.scene.initialState())))
          << task.scene.pairName(decision.pair) << "\n"
          << mutated;
    }
  }
  RecordProperty("robot_urdf_readable", readable);
}

}  // namespace
