#pragma once

#include "fesd_trajopt/nlp/nlp_assembly.h"

namespace fesd {

/// Memory one solve of `nlp` needs, estimated before Ipopt starts (MiB): the sparse direct
/// factorisation of the KKT matrix dominates, and its fronts are about one finite element's KKT
/// rows, densely coupled (through the contact pairs), so its factors grow as (n + m)^2 / elements;
/// Ipopt's and MUMPS' vectors and the matrix itself as its nonzeros. Fitted to the showcase with
/// 3 and 7 passive discs in reach (peaks 46 and 147 MiB above the process's start, estimates 37
/// and 192 MiB): a guard against requests that would take the machine, not a prediction.
double estimatedSolverMib(const NlpAssembly& nlp, int elements);

}  // namespace fesd
