// derivatives: cost of one model evaluation (value, Jacobian, weighted Hessian) per technique.
#include <chrono>
#include <cstdio>
#include <random>
#include <vector>

#include "commands.h"
#include "fesd_trajopt/examples/circle_example.h"

namespace fesd_bench {
namespace {

/// Nanoseconds per call of value + Jacobian + weighted Hessian, at fixed random points.
double nanosecondsPerEvaluation(const fesd::SmoothFunction& function, int repetitions) {
  std::mt19937 random(1);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::vector<double> z(function.inputSize()), w(function.outputSize()), y(function.outputSize()),
      jacobian(function.jacobianPattern().nonzeros()),
      hessian(function.hessianPattern().nonzeros());
  for (double& v : z) v = uniform(random);
  for (double& v : w) v = uniform(random);
  const auto start = std::chrono::steady_clock::now();
  for (int r = 0; r < repetitions; ++r) {
    z[0] += 1e-9;  // keep the compiler from hoisting the work
    function.evaluate(z.data(), y.data());
    function.evaluateJacobian(z.data(), jacobian.data());
    function.evaluateHessian(z.data(), w.data(), hessian.data());
  }
  return 1e9 * std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() /
         repetitions;
}

void report(const char* model, const char* technique, const char* function_name,
            const fesd::SmoothFunction& function, int repetitions) {
  std::printf("%s,%s,%s,%d,%d,%.1f\n", model, technique, function_name,
              function.jacobianPattern().nonzeros(), function.hessianPattern().nonzeros(),
              nanosecondsPerEvaluation(function, repetitions));
}

}  // namespace

int derivatives(const Arguments& args) {
  const int repetitions = args.integer("repeat", 200000);
  args.rejectUnused();
  std::printf("model,technique,function,jacobian_nnz,hessian_nnz,ns_per_evaluation\n");
  const auto analytic = fesd::circle_example::model();
  const auto autodiff = fesd::circle_example::autodiffModel();
  report("circle_example", "analytic", "velocity", *analytic->velocity(), repetitions);
  report("circle_example", "eigen_autodiff", "velocity", *autodiff->velocity(), repetitions);
  report("circle_example", "analytic", "constraints", *analytic->constraints(), repetitions);
  report("circle_example", "eigen_autodiff", "constraints", *autodiff->constraints(), repetitions);
  return 0;
}

}  // namespace fesd_bench
