#!/bin/sh
# stable_step.sh - the largest stable explicit step of a spectral scene, found by bisection
# (docs/spectral.md, "Stable steps from the operator")
#
# Usage: tools/stable_step.sh BUILD_DIR EXE LO HI TFINAL [scene options...]
#
# Runs BUILD_DIR/examples/spectral/EXE (diffusion or advection) with the scene options and
# -ts_type rk -ts_rk_type 3 (override with later options, e.g. -ts_rk_type 4) -ts_dt dt to
# TFINAL, with the growth check off, and calls a step stable when the run ends and the RMS of
# its grid solution at TFINAL is below 10 (u0 = exp(-(x - pi)^2) has RMS 0.45 and maximum 1; an
# unstable step grows to 1e6 or overflows). LO must be stable and HI unstable; the bracket is
# halved geometrically until HI / LO < 1.005. Prints "largest_stable <lo> unstable <hi>" and the
# operator's estimate (the step the example takes without -ts_dt).
#   tools/stable_step.sh build diffusion 1e-5 2e-4 1 -options_file_yaml scene.yaml
# (a scene file that sets ts_dt would override the bisection's -ts_dt: give the scene's
# -spectral_* options or a YAML file with the spectral: block only).
set -eu
. "$(dirname "$0")/script_common.sh"
[ $# -ge 5 ] || { sed -n '4,9p' "$0" >&2; exit 1; }
exe="$(cd "$1" && pwd)/examples/spectral/$2"; lo=$3; hi=$4; tf=$5
shift 5
require_built "$exe"
set_mpiexec
make_workdir stable_step
stable() {
  rm -f "$tmp"/g_*.txt
  (cd "$tmp" && $MPIEXEC "$exe" -ts_type rk -ts_rk_type 3 "$@" -ts_dt "$dt" -output_times "$tf" -grid_solution_file g \
    -no_timing -spectral_growth_bound 0 >run.log 2>&1) || return 1
  awk '{s += $2 * $2; n++} END {r = sqrt(s / n); exit !(r == r && r < 10)}' "$tmp"/g_*.txt
}
dt=$lo
stable "$@" || { echo "$0: LO = $lo is not stable (see a run: $MPIEXEC $exe $* -ts_dt $lo)" >&2; exit 1; }
while awk -v a="$lo" -v b="$hi" 'BEGIN {exit !(b / a >= 1.005)}'; do
  dt=$(awk -v a="$lo" -v b="$hi" 'BEGIN {printf "%.6g", sqrt(a * b)}')
  if stable "$@"; then lo=$dt; else hi=$dt; fi
done
est=$(cd "$tmp" && $MPIEXEC "$exe" -ts_type rk -ts_rk_type 3 "$@" -output_times 1e-12 -no_timing | sed -n 's/^ts_type .*time step //p')
echo "largest_stable $lo unstable $hi estimate $est"
