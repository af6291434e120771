#pragma once

#include <cstdint>
#include <vector>

namespace fesd::linalg {

/// A symmetric matrix's sparsity: its lower triangle in compressed columns (0-based), rows sorted
/// within each column, every diagonal entry present.
struct LowerPattern {
  int dimension = 0;
  std::vector<int> column_starts;  ///< dimension + 1 offsets into rows
  std::vector<int> rows;
  int64_t nonzeros() const { return static_cast<int64_t>(rows.size()); }
  bool operator==(const LowerPattern& other) const {
    return dimension == other.dimension && column_starts == other.column_starts &&
           rows == other.rows;
  }
};

/// Reads a lower-triangle pattern in compressed columns with `base` 0 or 1 (Fortran), checking
/// what the factorisation relies on; throws std::invalid_argument naming the first fault.
LowerPattern lowerPattern(int dimension, const int* column_starts, const int* rows, int base);

enum class FillOrdering {
  kAuto,   ///< AMD, and METIS as well where AMD's fill is large; the one with fewer flops
  kAmd,    ///< approximate minimum degree (SuiteSparse AMD)
  kMetis,  ///< nested dissection (METIS)
};

/// A column block of the factor: `columns` consecutive pivots (in the fill-reducing order) that
/// share one row structure, factorised together as a dense front.
struct Supernode {
  int first_column = 0;
  int columns = 0;
  int rows = 0;               ///< rows of the front: its own columns first, then the rows below
  int64_t row_offset = 0;     ///< where its rows start in SupernodalAnalysis::row_indices
  int64_t factor_offset = 0;  ///< where its rows x columns block starts in the factor's values
  int parent = -1;            ///< the supernode its update goes to; -1 for a root
  int below() const { return rows - columns; }
};

/// Everything a multifrontal LDL^T factorisation of one sparsity pattern needs that does not
/// depend on the values: the fill-reducing order, the supernodes in a postorder of their
/// assembly tree, where every input entry goes and where every update lands. Computed once per
/// pattern and shared, read-only, by every factorisation of it.
class SupernodalAnalysis {
 public:
  /// CHOLMOD chooses the order (`ordering`'s method, kAuto: AMD, METIS where AMD fills much).
  SupernodalAnalysis(const LowerPattern& pattern, FillOrdering ordering);
  /// The order is given (`order[k]`: the index eliminated k-th, before the postorder of the
  /// elimination tree); `method` says where it came from.
  SupernodalAnalysis(const LowerPattern& pattern, const std::vector<int>& order,
                     FillOrdering method);

  int dimension() const { return dimension_; }
  const LowerPattern& pattern() const { return pattern_; }
  FillOrdering ordering() const { return ordering_; }
  const std::vector<Supernode>& supernodes() const { return supernodes_; }
  /// position in the elimination order of every original index, and its inverse
  const std::vector<int>& positionOf() const { return position_of_; }
  const std::vector<int>& indexAt() const { return index_at_; }
  /// every supernode's rows, in elimination positions, ascending
  const std::vector<int>& rowIndices() const { return row_indices_; }
  /// The input entries grouped by supernode, as they are assembled: supernode s takes entries
  /// assembly_entries[assembly_starts[s] .. assembly_starts[s + 1]) (indices in the pattern's
  /// order), each at its row among the supernode's rows and its column among its columns.
  const std::vector<int64_t>& assemblyStarts() const { return assembly_starts_; }
  const std::vector<int>& assemblyEntries() const { return assembly_entries_; }
  const std::vector<int>& assemblyRows() const { return assembly_rows_; }
  const std::vector<int>& assemblyColumns() const { return assembly_columns_; }

  int64_t factorEntries() const { return factor_entries_; }  ///< stored values of L (with D)
  int64_t patternEntries() const { return pattern_entries_; }
  double flops() const { return flops_; }  ///< multiply-adds of one factorisation, about
  int largestFront() const { return largest_front_; }  ///< rows, without delays
  int64_t largestFrontEntries() const;
  /// doubles the update-matrix stack holds at most during a factorisation without delays
  int64_t stackEntries() const { return stack_entries_; }
  int treeDepth() const { return tree_depth_; }

 private:
  void build(const LowerPattern& pattern, const std::vector<int>* order);
  void buildEntryMap(const LowerPattern& pattern, const std::vector<int>& supernode_of);
  void measure();

  int dimension_ = 0;
  LowerPattern pattern_;
  FillOrdering ordering_ = FillOrdering::kAmd;
  std::vector<int> position_of_, index_at_;
  std::vector<Supernode> supernodes_;
  std::vector<int> row_indices_;
  std::vector<int64_t> assembly_starts_;
  std::vector<int> assembly_entries_, assembly_rows_, assembly_columns_;
  int64_t factor_entries_ = 0, pattern_entries_ = 0, stack_entries_ = 0;
  double flops_ = 0.0;
  int largest_front_ = 0, tree_depth_ = 0;
};

}  // namespace fesd::linalg
