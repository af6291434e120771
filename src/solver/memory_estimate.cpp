#include "fesd_trajopt/solver/memory_estimate.h"

#include <algorithm>

namespace fesd {
namespace {

constexpr double kBytesPerFactorEntry = 8.0;
constexpr double kBytesPerKktNonzero = 100.0;
constexpr double kMib = 1024.0 * 1024.0;

}  // namespace

double estimatedSolverMib(const NlpAssembly& nlp, int elements) {
  const double rows = static_cast<double>(nlp.numVariables()) + nlp.numConstraints();
  const double nonzeros = static_cast<double>(nlp.jacobianPattern().nonzeros()) +
                          nlp.hessianPattern().nonzeros() + rows;
  const double factors = kBytesPerFactorEntry * rows * rows / std::max(1, elements);
  return (factors + kBytesPerKktNonzero * nonzeros) / kMib;
}

}  // namespace fesd
