#include "ipopt_linear_solver.h"

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstring>
#include <exception>
#include <memory>
#include <mutex>
#include <new>
#include <stdexcept>

#include <coin/HSLLoader.h>

#include "fesd_trajopt/linalg/analysis_cache.h"
#include "fesd_trajopt/linalg/multifrontal_ldlt.h"
#include "fesd_trajopt/solver/kkt_capture.h"

namespace fesd {

namespace ma97 {

// The layout of Debian's libipopt (x86-64), read from Ipopt 3.11.9's interface.
static_assert(sizeof(Control) == 216 && offsetof(Control, multiplier) == 16 &&
                  offsetof(Control, small) == 40 && offsetof(Control, u) == 48 &&
                  offsetof(Control, factor_min) == 72 && offsetof(Control, consist_tol) == 104 &&
                  offsetof(Control, rspare) == 136,
              "ma97_control_d as Ipopt 3.11.9 was compiled");
static_assert(sizeof(Info) == 176 && offsetof(Info, num_delay) == 36 &&
                  offsetof(Info, num_factor) == 40 && offsetof(Info, num_neg) == 56 &&
                  offsetof(Info, ordering) == 68 && offsetof(Info, rspare) == 96,
              "ma97_info_d as Ipopt 3.11.9 was compiled");

namespace {

// MA97's flags that Ipopt tells apart: 0 success, -7 singular, anything else negative fatal.
constexpr int kSuccess = 0;
constexpr int kCallSequenceError = -1;
constexpr int kBadPattern = -3;
constexpr int kBadJob = -6;  // not one Ipopt sends
constexpr int kSingular = -7;
constexpr int kNonFinite = -8;
constexpr int kOutOfMemory = -9;
constexpr int kAmdOrdering = 1, kMetisOrdering = 3;

/// Wall time since construction, read only when a KktCapture watches (a clock read per call
/// otherwise costs what the capture measures).
class CaptureClock {
 public:
  CaptureClock() : start_(KktCapture::active() ? Clock::now() : Clock::time_point{}) {}
  double seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

 private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point start_;
};

/// What analyse hands to factor: the shared analysis and the constraint rows.
struct Analysis {
  std::shared_ptr<const linalg::SupernodalAnalysis> symbolic;
  std::vector<char> constraint;
};

/// What factor keeps for the solves: the numeric factor and the info it reported.
struct Factor {
  std::unique_ptr<linalg::MultifrontalLdlt> ldlt;
  Info info;
};

linalg::FillOrdering fillOrdering(int ordering) {
  if (ordering == kAmdOrdering) return linalg::FillOrdering::kAmd;
  if (ordering == kMetisOrdering) return linalg::FillOrdering::kMetis;
  return linalg::FillOrdering::kAuto;
}

/// MA97's pivoting controls as Ipopt sets them: u (1e-8, raised towards 1e-4 when Ipopt asks for
/// better solutions) and small (1e-20).
linalg::PivotSettings pivotSettings(const Control& control) {
  linalg::PivotSettings settings;
  settings.threshold = control.u;
  settings.zero = control.small;
  return settings;
}

void describe(const linalg::SupernodalAnalysis& symbolic, Info& info) {
  info.matrix_rank = symbolic.dimension();
  info.maxfront = symbolic.largestFront();
  info.maxdepth = symbolic.treeDepth();
  info.num_factor = static_cast<long>(symbolic.factorEntries());
  info.num_flops = static_cast<long>(symbolic.flops());
  info.num_sup = static_cast<int>(symbolic.supernodes().size());
  info.ordering = symbolic.ordering() == linalg::FillOrdering::kAmd ? kAmdOrdering : kMetisOrdering;
}

/// The constraint rows of Ipopt's augmented system [W + D_x, 0, J_c^T, J_d^T; 0, D_s, 0, -I;
/// J_c, 0, -d_c, 0; J_d, -I, 0, -d_d]: they come last and, alone among the columns, have
/// nothing below their diagonal in the lower triangle.
std::vector<char> augmentedSystemConstraints(const linalg::LowerPattern& pattern) {
  std::vector<char> constraint(pattern.dimension, 0);
  for (int j = pattern.dimension - 1; j >= 0; --j) {
    if (pattern.column_starts[j + 1] - pattern.column_starts[j] != 1) break;
    constraint[j] = 1;
  }
  return constraint;
}

/// Runs a call, turning exceptions into MA97 flags: Ipopt then takes its own fallbacks.
template <class Call>
void guarded(Info* info, Call call) {
  try {
    call();
  } catch (const std::bad_alloc&) {
    info->flag = kOutOfMemory;
  } catch (const std::invalid_argument&) {
    info->flag = kBadPattern;
  } catch (const std::exception&) {
    info->flag = kCallSequenceError;
  }
}

}  // namespace

/// Ipopt's Ma97SolverInterface (3.11.9, and 3.14 still) sets its count of negative pivots,
/// numneg_, only after a successful solve, but reads it after a factorisation with the wrong
/// inertia to choose its correction (fewer negative eigenvalues than constraints: a
/// rank-deficient Jacobian, delta_c; more: delta_x). Before the first solve of an NLP that is
/// uninitialised heap memory, and then a stale count: the same request took other corrections in
/// other runs of the node (different answers, seen in the load test). The interface hands
/// ma97_factor its own members &akeep_ and val_; in 3.11.9's layout (int ndim_; double* val_;
/// int numneg_; int numdelay_; void* akeep_, with ndim_ in its base class' tail padding) numneg_
/// sits 8 bytes before akeep_. Only when ndim_ and val_ are found where that layout puts them is
/// the factorisation's count written there, as a fixed Ipopt would have it.
bool tellIpoptTheInertia(void** akeep, const double* val, int dimension, int negative) {
  char* akeep_member = reinterpret_cast<char*>(akeep);
  const double* val_member;
  int ndim_member;
  std::memcpy(&val_member, akeep_member - 16, sizeof val_member);
  std::memcpy(&ndim_member, akeep_member - 20, sizeof ndim_member);
  if (val_member != val || ndim_member != dimension) return false;  // not the layout we know
  std::memcpy(akeep_member - 8, &negative, sizeof negative);
  return true;
}

void defaultControl(Control* control) {
  *control = Control{};
  control->action = 1;
  control->nemin = 8;
  control->multiplier = 1.1;
  control->ordering = 5;  // MA97's "auto": ours picks AMD or METIS
  control->small = 1e-20;
  control->u = 0.01;
  control->unit_diagnostics = 6;
  control->unit_error = 6;
  control->unit_warning = 6;
  control->factor_min = 20000000;
  control->solve_min = 100000;
  control->consist_tol = 2.2e-16;
}

void analyse(int, int n, const int ptr[], const int row[], double[], void** akeep,
             const Control* control, Info* info, int[]) {
  *info = Info{};
  *akeep = nullptr;
  const CaptureClock clock;
  guarded(info, [&] {
    const linalg::LowerPattern pattern =
        linalg::lowerPattern(n, ptr, row, control->f_arrays ? 1 : 0);
    auto analysis = std::make_unique<Analysis>();
    analysis->constraint = augmentedSystemConstraints(pattern);
    analysis->symbolic = linalg::AnalysisCache::process().analysis(pattern, analysis->constraint,
                                                                   fillOrdering(control->ordering));
    describe(*analysis->symbolic, *info);
    *akeep = analysis.release();
  });
  if (KktCapture* capture = KktCapture::active()) {
    KktCapture::Totals& totals = capture->mutableTotals();
    ++totals.analyses;
    totals.analysis_seconds += clock.seconds();
  }
}

void factor(int, const int ptr[], const int row[], const double val[], void** akeep, void** fkeep,
            const Control* control, Info* info, const double scale[]) {
  *info = Info{};
  if (*akeep == nullptr) {  // Ipopt analyses first, also for the orderings that need values
    info->flag = kCallSequenceError;
    return;
  }
  const CaptureClock clock;
  guarded(info, [&] {
    const Analysis& analysis = *static_cast<const Analysis*>(*akeep);
    if (*fkeep == nullptr) {
      auto created = std::make_unique<Factor>();
      created->ldlt = std::make_unique<linalg::MultifrontalLdlt>(analysis.symbolic);
      *fkeep = created.release();
    }
    Factor& factor = *static_cast<Factor*>(*fkeep);
    const linalg::FactorReport report = factor.ldlt->factor(val, pivotSettings(*control));
    describe(*analysis.symbolic, *info);
    info->num_factor = static_cast<long>(factor.ldlt->factorEntries());
    info->num_delay = report.delayed;
    info->num_two = report.two_by_two;
    info->num_neg = report.negative;
    info->flag = !report.finite ? kNonFinite : report.zero > 0 ? kSingular : kSuccess;
    const bool told =
        tellIpoptTheInertia(akeep, val, analysis.symbolic->dimension(), report.negative);
    if (report.zero > 0) info->matrix_rank = analysis.symbolic->dimension() - report.zero;
    if (control->scaling > 0 && scale != nullptr) {
      // Ipopt keeps and hands back the scaling MA97 computed; ours is the identity.
      double* written = const_cast<double*>(scale);
      std::fill(written, written + analysis.symbolic->dimension(), 1.0);
    }
    factor.info = *info;
    if (KktCapture* capture = KktCapture::active()) {
      KktCapture::Totals& totals = capture->mutableTotals();
      ++totals.factorisations;
      totals.factor_seconds += clock.seconds();
      totals.delayed_pivots += report.delayed;
      totals.inertia_told += told;
      totals.two_by_two_pivots += report.two_by_two;
      const linalg::SupernodalAnalysis& symbolic = *analysis.symbolic;
      if (symbolic.dimension() > totals.largest_dimension) {
        totals.largest_dimension = symbolic.dimension();
        totals.factor_entries = symbolic.factorEntries();
      }
      if (capture->wantsMatrix()) {
        capture->addMatrix({symbolic.pattern(),
                            std::vector<double>(val, val + symbolic.patternEntries()),
                            analysis.constraint, report.negative});
      }
    }
  });
}

void factorSolve(int matrix_type, const int ptr[], const int row[], const double val[], int nrhs,
                 double x[], int ldx, void** akeep, void** fkeep, const Control* control,
                 Info* info, const double scale[]) {
  factor(matrix_type, ptr, row, val, akeep, fkeep, control, info, scale);
  if (info->flag >= 0) solve(0, nrhs, x, ldx, akeep, fkeep, control, info);
}

void solve(int job, int nrhs, double* x, int ldx, void**, void** fkeep, const Control*,
           Info* info) {
  if (*fkeep == nullptr) {
    *info = Info{};
    info->flag = kCallSequenceError;
    return;
  }
  Factor& factor = *static_cast<Factor*>(*fkeep);
  *info = factor.info;  // Ipopt reads the inertia from the solve's info
  if (job != 0) {
    info->flag = kBadJob;
    return;
  }
  if (!factor.ldlt->factorised()) {
    info->flag = kCallSequenceError;
    return;
  }
  const CaptureClock clock;
  for (int k = 0; k < nrhs; ++k) factor.ldlt->solve(x + static_cast<ptrdiff_t>(k) * ldx);
  if (KktCapture* capture = KktCapture::active()) {
    KktCapture::Totals& totals = capture->mutableTotals();
    totals.solves += nrhs;
    totals.solve_seconds += clock.seconds();
  }
}

void finalise(void** akeep, void** fkeep) {
  delete static_cast<Factor*>(*fkeep);
  *fkeep = nullptr;
  freeAkeep(akeep);
}

void freeAkeep(void** akeep) {
  delete static_cast<Analysis*>(*akeep);
  *akeep = nullptr;
}

}  // namespace ma97

namespace {

// Ipopt's function types name its own (incomplete) structs; ours have the same layout.
ma97::Control* ours(struct ma97_control* control) {
  return reinterpret_cast<ma97::Control*>(control);
}
const ma97::Control* ours(const struct ma97_control* control) {
  return reinterpret_cast<const ma97::Control*>(control);
}
ma97::Info* ours(struct ma97_info* info) {
  return reinterpret_cast<ma97::Info*>(info);
}

}  // namespace

void registerLdltAsMa97() {
  static std::once_flag registered;
  std::call_once(registered, [] {
    LSL_setMA97(
        [](struct ma97_control* control) { ma97::defaultControl(ours(control)); },
        [](const int check, const int n, const int ptr[], const int row[], double val[],
           void** akeep, const struct ma97_control* control, struct ma97_info* info, int order[]) {
          ma97::analyse(check, n, ptr, row, val, akeep, ours(control), ours(info), order);
        },
        [](const int matrix_type, const int ptr[], const int row[], const double val[],
           void** akeep, void** fkeep, const struct ma97_control* control, struct ma97_info* info,
           const double scale[]) {
          ma97::factor(matrix_type, ptr, row, val, akeep, fkeep, ours(control), ours(info), scale);
        },
        [](const int matrix_type, const int ptr[], const int row[], const double val[],
           const int nrhs, double x[], const int ldx, void** akeep, void** fkeep,
           const struct ma97_control* control, struct ma97_info* info, const double scale[]) {
          ma97::factorSolve(matrix_type, ptr, row, val, nrhs, x, ldx, akeep, fkeep, ours(control),
                            ours(info), scale);
        },
        [](const int job, const int nrhs, double* x, const int ldx, void** akeep, void** fkeep,
           const struct ma97_control* control, struct ma97_info* info) {
          ma97::solve(job, nrhs, x, ldx, akeep, fkeep, ours(control), ours(info));
        },
        [](void** akeep, void** fkeep) { ma97::finalise(akeep, fkeep); },
        [](void** akeep) { ma97::freeAkeep(akeep); });
  });
}

}  // namespace fesd
