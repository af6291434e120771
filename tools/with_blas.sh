#!/usr/bin/env bash
# Runs a command under one of the BLAS/LAPACK builds Debian offers, whatever the system's
# alternative points to, so that results can be compared across the kernels MUMPS may get:
#
#   tools/with_blas.sh VARIANT CMD [ARGS...]   run CMD under VARIANT
#   tools/with_blas.sh all CMD [ARGS...]       run CMD under every variant in turn
#   tools/with_blas.sh list                    the variants and the library each one loads
#
# Variants: reference (libblas3 + liblapack3), openblas-prescott, openblas-haswell,
# openblas-skylakex (libopenblas0-pthread with OPENBLAS_CORETYPE set), system (as installed).
set -euo pipefail

LIB_DIR=/usr/lib/x86_64-linux-gnu
VARIANTS=(reference openblas-prescott openblas-haswell openblas-skylakex)

usage() {
  sed -n '2,10s/^# \{0,1\}//p' "$0" >&2
  exit 2
}

# Prints the environment assignments of a variant (one per line), or fails for an unknown one.
variant_environment() {
  case "$1" in
    reference) echo "LD_LIBRARY_PATH=$LIB_DIR/blas:$LIB_DIR/lapack${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" ;;
    openblas-*)
      local core
      case "$1" in
        openblas-prescott) core=Prescott ;;
        openblas-haswell) core=Haswell ;;
        openblas-skylakex) core=SkylakeX ;;
        *) return 1 ;;
      esac
      [ -e "$LIB_DIR/openblas-pthread/libblas.so.3" ] || {
        echo "with_blas.sh: $1 needs Debian's libopenblas0-pthread" >&2
        return 1
      }
      echo "LD_LIBRARY_PATH=$LIB_DIR/openblas-pthread${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
      echo "OPENBLAS_CORETYPE=$core"
      ;;
    system) ;;
    *) return 1 ;;
  esac
}

run_variant() {
  local variant="$1"
  shift
  local assignments
  assignments=$(variant_environment "$variant") || {
    echo "with_blas.sh: unknown or unavailable variant '$variant'" >&2
    return 2
  }
  local environment=()
  [ -n "$assignments" ] && mapfile -t environment <<<"$assignments"
  env ${environment[@]+"${environment[@]}"} FESD_BLAS_VARIANT="$variant" "$@"
}

# The BLAS/LAPACK libraries the dynamic loader gives MUMPS under a variant.
loaded_blas() {
  run_variant "$1" ldd "$LIB_DIR/libdmumps_seq-5.5.so" |
    awk '/lib(open)?blas|liblapack/ {printf "%s%s", sep, $3; sep = " "}'
}

[ $# -ge 1 ] || usage
case "$1" in
  list)
    for variant in "${VARIANTS[@]}" system; do
      printf '%-18s %s\n' "$variant" "$(loaded_blas "$variant" 2>/dev/null || echo unavailable)"
    done
    ;;
  all)
    shift
    [ $# -ge 1 ] || usage
    status=0
    for variant in "${VARIANTS[@]}"; do
      echo "== BLAS variant: $variant"
      run_variant "$variant" "$@" || status=$?
    done
    exit "$status"
    ;;
  -h | --help) usage ;;
  *)
    variant="$1"
    shift
    [ $# -ge 1 ] || usage
    run_variant "$variant" "$@"
    ;;
esac
