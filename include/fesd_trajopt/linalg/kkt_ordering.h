#pragma once

#include <memory>
#include <vector>

#include "fesd_trajopt/linalg/supernodal_analysis.h"

namespace fesd::linalg {

/// A fill-reducing order for a saddle-point (KKT) matrix whose `constraint` indices have zero
/// diagonals. Such a row has no pivot until one of its primal neighbours is eliminated; where a
/// plain ordering puts it first, the factorisation has to delay it to a later front (417 delayed
/// columns per factorisation on the showcase's 2670-row KKT matrices, 1.9x the time). Here each
/// constraint is matched with a primal neighbour of low degree (greedily), the graph with every
/// matched pair as one node is ordered (AMD or METIS), and each pair comes out primal first.
std::vector<int> matchedOrdering(const LowerPattern& pattern, const std::vector<char>& constraint,
                                 FillOrdering method);

/// AMD's largest front (rows) from which kAuto analyses with METIS as well.
constexpr int kLargeFront = 128;

/// The analysis of a KKT matrix in a matched ordering: AMD, or METIS as well where AMD's
/// factor is large (CHOLMOD's rule: more than 500 flops per factor entry and five times the
/// matrix' entries) or its largest front has kLargeFront rows or more, whichever needs fewer
/// flops; kAmd or kMetis only that one.
std::shared_ptr<const SupernodalAnalysis> analyseKkt(const LowerPattern& pattern,
                                                     const std::vector<char>& constraint,
                                                     FillOrdering ordering);

}  // namespace fesd::linalg
