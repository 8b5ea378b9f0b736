#!/bin/sh
# spectral_figures.sh - the figures and measurements of docs/spectral.md (the paper's sparse
# spectral experiments):
#   spectral_diffusion_solutions.{png,svg}  u at t = 0.25, 0.5, 0.75, 1: DNS against VSHMM
#   spectral_diffusion_spectrum.{png,svg}   log10 |u_k| (unitary DFT) over time, clusters marked
#   spectral_advection_solutions.{png,svg}  u at t = 9, 18, 27, 36: DNS against VSHMM
#   spectral_advection_spectrum.{png,svg}   log10 |u_k| over time, clusters marked
#   spectral_results.txt                    the work and error lines of every run
#
# Usage: docs/figures/spectral_figures.sh BUILD_DIR      (called by `make figures`)
#   BUILD_DIR is the CMake build tree (examples/spectral/diffusion, examples/spectral/advection).
#   Needs gnuplot (pngcairo and svg terminals). MPIEXEC as in tools/script_common.sh. Takes about two
#   minutes, most of it the diffusion DNS (3e6 RK3 stages with N = 2048). With
#   SPECTRAL_CONVERGENCE=1 it also runs the refinement studies of the references (dt halved;
#   N doubled), about 15 minutes more.

set -eu

if [ $# -ne 1 ]; then
  echo "usage: $0 BUILD_DIR" >&2
  exit 2
fi
build=$(cd "$1" && pwd) # absolute: the runs start in a temporary directory
outdir=$(cd "$(dirname "$0")" && pwd)
scenes=$(cd "$outdir/../../examples/scenes" && pwd)
diff=$build/examples/spectral/diffusion
adv=$build/examples/spectral/advection
. "$outdir/../../tools/script_common.sh"
require_built "$diff" "$adv"
require_gnuplot
set_mpiexec
make_workdir vshmm-spectral-figures
results=$outdir/spectral_results.txt

run() { # run NAME EXE OPTIONS...: stdout to $tmp/NAME.out, its work/error lines to the results
  name=$1
  exe=$2
  shift 2
  echo "  $name: $(basename "$exe") $*"
  # shellcheck disable=SC2086
  if ! (cd "$tmp" && $MPIEXEC "$exe" "$@") > "$tmp/$name.out" 2> "$tmp/$name.err"; then
    echo "$0: the $name run failed:" >&2
    cat "$tmp/$name.out" "$tmp/$name.err" >&2
    exit 1
  fi
  {
    echo "## $name: $(basename "$exe") $*" | sed "s#$tmp/##g; s#$scenes#examples/scenes#g"
    grep -E "^(output|compare|ts_type|mode|  K[0-9]|cluster)" "$tmp/$name.out" | sed 's/ file [^ ]*$//'
    echo
  } >> "$results"
}

{
  echo "# docs/figures/spectral_figures.sh, $(date -u +%Y-%m-%d) on $(uname -m), $(nproc) cores"
  echo "# 'output' lines: work so far (rhs_evaluations = evaluations of a right-hand-side field,"
  echo "# full or VSHMM level), wall_time in seconds; 'compare' lines: error against the DNS reference."
  echo
} > "$results"

# ---------------------------------------------------------------------------------------------
echo "1. multiscale diffusion (N = 2048)"
yd=$scenes/diffusion.yaml
run diff_dns "$diff" -options_file_yaml "$yd" -spectral_mode dns -ts_type rk -ts_rk_type 3 -ts_dt 1e-6 \
  -grid_solution_file diffusion_dns -spectrum_file "$tmp/diffusion_spectrum.txt" -spectrum_interval 0.005
run diff_vshmm "$diff" -options_file_yaml "$yd" -grid_solution_file diffusion_vshmm -compare_grid_solution diffusion_dns
run diff_vshmm_matrix "$diff" -options_file_yaml "$yd" -spectral_evaluation matrix -compare_grid_solution diffusion_dns
run diff_sparse_dt1e-5 "$diff" -options_file_yaml "$yd" -ts_type rk -ts_rk_type 3 -ts_dt 1e-5 -compare_grid_solution diffusion_dns
run diff_sparse_dt5e-5 "$diff" -options_file_yaml "$yd" -ts_type rk -ts_rk_type 3 -ts_dt 5e-5 -compare_grid_solution diffusion_dns
run diff_sparse_dt1e-5_matrix "$diff" -options_file_yaml "$yd" -spectral_evaluation matrix -ts_type rk -ts_rk_type 3 -ts_dt 1e-5 -compare_grid_solution diffusion_dns
run diff_sparse9_dt5e-6 "$diff" -options_file_yaml "$yd" -spectral_clusters 0:6,58:70,122:134,186:198,250:262,314:326,378:390,506:518 \
  -ts_type rk -ts_rk_type 3 -ts_dt 5e-6 -compare_grid_solution diffusion_dns
run diff_detect "$diff" -options_file_yaml "$yd" -spectral_clusters none -spectral_cluster_detect file -spectral_cluster_detect_file diffusion_dns_1.txt -spectral_cluster_gap 2 \
  -spectral_cluster_normalization unitary -spectral_cluster_lambda 3.1622776601683794e-3 -spectral_cluster_fill_holes false -spectral_cluster_scale_separation 1 -output_times 0.001

echo "2. multiscale advection (N = 1024)"
ya=$scenes/advection.yaml
run adv_dns "$adv" -options_file_yaml "$ya" -spectral_mode dns -ts_type rk -ts_rk_type 3 -ts_dt 1.6e-4 \
  -grid_solution_file advection_dns -spectrum_file "$tmp/advection_spectrum.txt" -spectrum_interval 0.25
run adv_vshmm "$adv" -options_file_yaml "$ya" -grid_solution_file advection_vshmm -compare_grid_solution advection_dns
run adv_sparse_dt1e-3 "$adv" -options_file_yaml "$ya" -ts_type rk -ts_rk_type 3 -ts_dt 1e-3 -compare_grid_solution advection_dns

if [ "${SPECTRAL_CONVERGENCE:-0}" = 1 ]; then
  echo "3. convergence of the references"
  run diff_dns_dt5e-7 "$diff" -options_file_yaml "$yd" -spectral_mode dns -ts_type rk -ts_rk_type 3 -ts_dt 5e-7 -compare_grid_solution diffusion_dns
  run adv_dns_dt8e-5 "$adv" -options_file_yaml "$ya" -spectral_mode dns -ts_type rk -ts_rk_type 3 -ts_dt 8e-5 -compare_grid_solution advection_dns
  run adv_dns_N2048 "$adv" -options_file_yaml "$ya" -spectral_grid_points 2048 -spectral_mode dns -ts_type rk -ts_rk_type 3 -ts_dt 8e-5 -grid_solution_file advection_dns_N2048
  run diff_dns_N4096 "$diff" -options_file_yaml "$yd" -spectral_grid_points 4096 -spectral_mode dns -ts_type rk -ts_rk_type 3 -ts_dt 2.5e-7 -grid_solution_file diffusion_dns_N4096
  { # the finer grid at the coarse grid's points (every other point)
    echo "## N refinement: relative L2 difference of N = 2048 (4096 for diffusion) and N = 1024 (2048) at the coarse grid points"
    for t in 0.25 0.5 0.75 1; do
      awk 'NR==FNR { if ((FNR - 1) % 2 == 0) f[(FNR - 1) / 2] = $2; next } { d = $2 - f[FNR - 1]; e += d * d; n += f[FNR - 1] ^ 2 } END { printf "diffusion t %s relative_l2_difference %.3e\n", t, sqrt(e / n) }' t=$t "$tmp/diffusion_dns_N4096_$t.txt" "$tmp/diffusion_dns_$t.txt"
    done
    for t in 9 18 27 36; do
      awk 'NR==FNR { if ((FNR - 1) % 2 == 0) f[(FNR - 1) / 2] = $2; next } { d = $2 - f[FNR - 1]; e += d * d; n += f[FNR - 1] ^ 2 } END { printf "advection t %s relative_l2_difference %.3e\n", t, sqrt(e / n) }' t=$t "$tmp/advection_dns_N2048_$t.txt" "$tmp/advection_dns_$t.txt"
    done
    echo
  } >> "$results"
fi

# ---------------------------------------------------------------------------------------------
echo "4. figures"
cd "$tmp"
# solutions: DNS (line) against VSHMM (points) at the four times
solutions() { # solutions NAME T1 T2 T3 T4 XTITLE
  name=$1
  gnuplot <<EOF
set key top right box opaque
set grid
set xrange [0:2*pi]
set xtics ("0" 0, "{/Symbol p}/2" pi/2, "{/Symbol p}" pi, "3{/Symbol p}/2" 3*pi/2, "2{/Symbol p}" 2*pi)
set xlabel "x"
do for [fmt in "png svg"] {
  if (fmt eq "png") { set terminal pngcairo size 1600,420 font "sans,11" } else { set terminal svg size 1600,420 font "sans,11" dynamic }
  set output "$outdir/spectral_${name}_solutions.".fmt
  set multiplot layout 1,4 title "$6"
  do for [t in "$2 $3 $4 $5"] {
    set title "t = ".t
    set ylabel (t eq "$2") ? "u(t, x)" : ""
    plot "${name}_dns_".t.".txt" using 1:2 with lines lw 2 lc rgb "#1f5fbf" title "DNS", \
         "${name}_vshmm_".t.".txt" every 16 using 1:2 with points pt 7 ps 0.45 lc rgb "#d62728" title "VSHMM"
  }
  unset multiplot
}
EOF
}
solutions diffusion 0.25 0.5 0.75 1 "Multiscale diffusion u_t = (d u_x)_x, N = 2048: DNS (RK3, dt = 1e-6) and VSHMM (dt = 1e-5, alpha = 150, 18, 1.5; every 16th grid point)"
solutions advection 9 18 27 36 "Multiscale advection u_t + a u_x = 0, N = 1024: DNS (RK3, dt = 1.6e-4) and VSHMM (dt = 1e-3, alpha = 26, 9, 2; every 16th grid point)"

# spectra: log10 of the unitary DFT magnitude sqrt(N) |c_k|; left over (k, t), right against k
# at a few times; the clusters as bands, the shrinkage value lambda = 10^-2.5 as a line
spectrum() { # spectrum NAME N KMAX TMAX INTERVAL "lo:hi ..." "t1 t2 ..." TITLE
  name=$1
  awk -v kmax="$3" -v n="$2" '/^#/ { next } NF == 0 { print; next } $2 <= kmax { v = $3 > 0 ? log(sqrt(n) * $3) / log(10) : -12; if (v < -12) v = -12; print $1, $2, v }' \
    "${name}_spectrum.txt" > "${name}_spectrum_k.txt"
  objs=""
  i=1
  for c in $6; do
    lo=${c%%:*}
    hi=${c##*:}
    objs="$objs
set object $i rect from $lo-0.5, graph 0 to $hi+0.5, graph 1 back fillstyle solid 0.15 noborder fc rgb '#2ca02c'"
    i=$((i + 1))
  done
  blocks=""
  for t in $7; do blocks="$blocks $(awk -v t="$t" -v h="$5" 'BEGIN { printf "%d", t / h + 0.5 }')"; done
  gnuplot <<EOF
set xrange [0:$3]
do for [fmt in "png svg"] {
  if (fmt eq "png") { set terminal pngcairo size 1500,560 font "sans,11" } else { set terminal svg size 1500,560 font "sans,11" dynamic }
  set output "$outdir/spectral_${name}_spectrum.".fmt
  set multiplot layout 1,2 title "$8"
  unset object
  set xlabel "wavenumber k"
  set ylabel "t"
  set yrange [0:$4]
  set cbrange [-8:1.5]
  set cblabel "log_{10} |u_k|"
  set palette defined (-8 "#000004", -5 "#3b0f70", -2.5 "#de4968", 0 "#fe9f6d", 1.5 "#fcfdbf")
  set title "DNS: log_{10} |u_k| over time"
  plot "${name}_spectrum_k.txt" using 2:1:3 with image notitle
  $objs
  set title "log_{10} |u_k| at a few times; shaded: the clusters K0..K3"
  set ylabel "log_{10} |u_k|"
  set yrange [-8:1.5]
  set grid
  set key bottom right box opaque
  plot for [b in "$blocks"] "${name}_spectrum_k.txt" every :::b::b using 2:3 with lines lw 1.5 title sprintf("t = %g", b * $5), \
       -2.5 with lines dt 2 lc rgb "black" title "lambda = 10^{-2.5}"
  unset multiplot
  unset grid
}
EOF
}
spectrum diffusion 2048 300 1 0.005 "0:3 62:66 192:193 255:257" "0 0.01 0.05 0.25 1" "Multiscale diffusion, DNS (N = 2048): Fourier coefficients (unitary DFT) and the clusters"
spectrum advection 1024 300 36 0.25 "0:24 40:88 114:162 246:266" "0 1 9 36" "Multiscale advection, DNS (N = 1024): Fourier coefficients (unitary DFT) and the clusters"

echo "written: $outdir/spectral_{diffusion,advection}_{solutions,spectrum}.{png,svg}, $results"
