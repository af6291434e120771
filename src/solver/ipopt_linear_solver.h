#pragma once

namespace fesd {

/// Makes our multifrontal LDL^T the solver Ipopt uses under `linear_solver ma97`: Debian's Ipopt
/// 3.11.9 has only MUMPS built in, but its HSL loader takes the MA97 functions from us
/// (LSL_setMA97). Idempotent and thread-safe; must run before an IpoptApplication is created.
void registerLdltAsMa97();

/// The MA97 entry points as Ipopt calls them, for tests (Ipopt's own structs, re-typed).
namespace ma97 {

struct Control {
  int f_arrays, action, nemin;
  double multiplier;
  int ordering, print_level, scaling;
  double small, u;
  int unit_diagnostics, unit_error, unit_warning;
  long factor_min;
  int solve_blas3;
  long solve_min;
  int solve_mf;
  double consist_tol;
  int ispare[5];
  double rspare[10];
};

struct Info {
  int flag, flag68, flag77, matrix_dup, matrix_rank, matrix_outrange, matrix_missing_diag, maxdepth,
      maxfront, num_delay;
  long num_factor, num_flops;
  int num_neg, num_sup, num_two, ordering, stat;
  int ispare[5];
  double rspare[10];
};

void defaultControl(Control* control);
void analyse(int check, int n, const int ptr[], const int row[], double val[], void** akeep,
             const Control* control, Info* info, int order[]);
void factor(int matrix_type, const int ptr[], const int row[], const double val[], void** akeep,
            void** fkeep, const Control* control, Info* info, const double scale[]);
void factorSolve(int matrix_type, const int ptr[], const int row[], const double val[], int nrhs,
                 double x[], int ldx, void** akeep, void** fkeep, const Control* control,
                 Info* info, const double scale[]);
void solve(int job, int nrhs, double* x, int ldx, void** akeep, void** fkeep,
           const Control* control, Info* info);
void finalise(void** akeep, void** fkeep);
/// Writes a factorisation's count of negative pivots into the Ipopt interface object that owns
/// `akeep` (its numneg_, which Ipopt reads after a wrong inertia but sets only after a solve),
/// if the members beside it are where Ipopt 3.11.9's layout puts them; true if written.
bool tellIpoptTheInertia(void** akeep, const double* val, int dimension, int negative);
void freeAkeep(void** akeep);

}  // namespace ma97

}  // namespace fesd
