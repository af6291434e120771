#include "fesd_trajopt/linalg/kkt_ordering.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>

#include <metis.h>
#include <suitesparse/amd.h>

namespace fesd::linalg {

namespace {

/// A symmetric graph in compressed columns (both triangles, no diagonal).
struct Graph {
  std::vector<int> starts, neighbours;
  int nodes() const { return static_cast<int>(starts.size()) - 1; }
  int degree(int i) const { return starts[i + 1] - starts[i]; }
};

Graph adjacency(const LowerPattern& pattern) {
  const int n = pattern.dimension;
  Graph graph;
  graph.starts.assign(n + 1, 0);
  for (int j = 0; j < n; ++j) {
    for (int e = pattern.column_starts[j] + 1; e < pattern.column_starts[j + 1]; ++e) {
      ++graph.starts[pattern.rows[e] + 1];
      ++graph.starts[j + 1];
    }
  }
  std::partial_sum(graph.starts.begin(), graph.starts.end(), graph.starts.begin());
  graph.neighbours.resize(graph.starts[n]);
  std::vector<int> next(graph.starts.begin(), graph.starts.end() - 1);
  for (int j = 0; j < n; ++j) {
    for (int e = pattern.column_starts[j] + 1; e < pattern.column_starts[j + 1]; ++e) {
      const int i = pattern.rows[e];
      graph.neighbours[next[i]++] = j;
      graph.neighbours[next[j]++] = i;
    }
  }
  return graph;
}

/// The graph with `node_of` merging indices into nodes (no self loops, no duplicates).
Graph compressed(const Graph& graph, const std::vector<int>& node_of, int nodes) {
  std::vector<std::vector<int>> members(nodes);
  for (int i = 0; i < graph.nodes(); ++i) members[node_of[i]].push_back(i);
  Graph result;
  result.starts.push_back(0);
  std::vector<int> seen(nodes, -1);
  for (int node = 0; node < nodes; ++node) {
    seen[node] = node;
    for (int i : members[node]) {
      for (int e = graph.starts[i]; e < graph.starts[i + 1]; ++e) {
        const int other = node_of[graph.neighbours[e]];
        if (seen[other] != node) {
          seen[other] = node;
          result.neighbours.push_back(other);
        }
      }
    }
    result.starts.push_back(static_cast<int>(result.neighbours.size()));
  }
  return result;
}

std::vector<int> amdOrder(const Graph& graph) {
  std::vector<int> order(graph.nodes());
  double control[AMD_CONTROL], info[AMD_INFO];
  amd_defaults(control);
  const int none = 0;  // AMD refuses a null array, even an empty one
  const int status = amd_order(graph.nodes(), graph.starts.data(),
                               graph.neighbours.empty() ? &none : graph.neighbours.data(),
                               order.data(), control, info);
  if (status < AMD_OK) throw std::runtime_error("AMD failed on the KKT graph");
  return order;
}

std::vector<int> metisOrder(Graph graph) {
  idx_t nodes = graph.nodes();
  std::vector<idx_t> order(nodes), inverse(nodes);
  if (nodes == 0) return {};
  if (graph.neighbours.empty()) graph.neighbours.push_back(0);  // METIS reads the array
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  const int status = METIS_NodeND(&nodes, graph.starts.data(), graph.neighbours.data(), nullptr,
                                  options, order.data(), inverse.data());
  if (status != METIS_OK) throw std::runtime_error("METIS failed on the KKT graph");
  return std::vector<int>(order.begin(), order.end());
}

/// When METIS is tried after AMD: CHOLMOD's rule (many flops per factor entry: 500, counting a
/// multiply-add as two; much fill), or a large front. A robot's contact pairs chain through the
/// horizon (cross complementarity), and AMD, eliminating those chains early, merges the state
/// blocks of many elements into fronts of hundreds of rows without tripping CHOLMOD's rule.
bool worthTryingMetis(const SupernodalAnalysis& analysis) {
  const double entries = static_cast<double>(analysis.factorEntries());
  return (analysis.flops() >= 250.0 * entries && entries >= 5.0 * analysis.patternEntries()) ||
         analysis.largestFront() >= kLargeFront;
}

}  // namespace

std::vector<int> matchedOrdering(const LowerPattern& pattern, const std::vector<char>& constraint,
                                 FillOrdering method) {
  const int n = pattern.dimension;
  if (static_cast<int>(constraint.size()) != n) {
    throw std::invalid_argument("matchedOrdering: one constraint flag per index");
  }
  const Graph graph = adjacency(pattern);
  // Greedy matching: each constraint takes its free primal neighbour of least degree (the pair
  // then adds least to the compressed graph); ties to the lowest index, so it is deterministic.
  std::vector<int> partner(n, -1);
  for (int r = 0; r < n; ++r) {
    if (!constraint[r]) continue;
    int best = -1;
    for (int e = graph.starts[r]; e < graph.starts[r + 1]; ++e) {
      const int j = graph.neighbours[e];
      if (constraint[j] || partner[j] >= 0) continue;
      if (best < 0 || graph.degree(j) < graph.degree(best) ||
          (graph.degree(j) == graph.degree(best) && j < best)) {
        best = j;
      }
    }
    if (best >= 0) {
      partner[r] = best;
      partner[best] = r;
    }
  }
  std::vector<int> node_of(n, -1), primal_of_node, constraint_of_node;
  for (int i = 0; i < n; ++i) {
    if (node_of[i] >= 0) continue;
    const int node = static_cast<int>(primal_of_node.size());
    const int other = partner[i];
    const int primal = other >= 0 && constraint[i] ? other : i;
    node_of[i] = node;
    if (other >= 0) node_of[other] = node;
    primal_of_node.push_back(primal);
    constraint_of_node.push_back(other >= 0 ? (primal == i ? other : i) : -1);
  }
  const Graph nodes = compressed(graph, node_of, static_cast<int>(primal_of_node.size()));
  const std::vector<int> node_order =
      method == FillOrdering::kMetis ? metisOrder(nodes) : amdOrder(nodes);
  std::vector<int> order;
  order.reserve(n);
  for (int node : node_order) {
    order.push_back(primal_of_node[node]);
    if (constraint_of_node[node] >= 0) order.push_back(constraint_of_node[node]);
  }
  return order;
}

std::shared_ptr<const SupernodalAnalysis> analyseKkt(const LowerPattern& pattern,
                                                     const std::vector<char>& constraint,
                                                     FillOrdering ordering) {
  auto analysed = [&](FillOrdering method) {
    return std::make_shared<const SupernodalAnalysis>(
        pattern, matchedOrdering(pattern, constraint, method), method);
  };
  if (ordering != FillOrdering::kAuto) return analysed(ordering);
  auto amd = analysed(FillOrdering::kAmd);
  if (!worthTryingMetis(*amd)) return amd;
  auto metis = analysed(FillOrdering::kMetis);
  return metis->flops() < amd->flops() ? metis : amd;
}

}  // namespace fesd::linalg
