#!/bin/sh
# make_figures.sh - the figures of docs/ode-experiments.md (the paper's ODE experiments):
#   dissipative.{png,svg}   xi(t): DNS, averaged equation, VSHMM with variable and constant steps
#   oscillatory.{png,svg}   I1(t), I2(t): converged DNS, VSHMM with constant and variable steps
#   torus.{png,svg}         60 sampling points of constant / variable mesoscopic steps on the torus
#
# Usage: docs/figures/make_figures.sh BUILD_DIR      (or `make figures`)
#   BUILD_DIR is the CMake build tree (examples/ode/dissipative, examples/ode/oscillatory,
#   tools/oscillatory_reference, tools/torus_sampling). The figures are written next to this
#   script; the CSV intermediates go to a temporary directory that is removed at the end.
#   Needs gnuplot (Debian: gnuplot-nox) with the pngcairo and svg terminals. Set MPIEXEC to use
#   another launcher (default: mpiexec -n 1, plus --allow-run-as-root --oversubscribe for Open
#   MPI when run as root). Takes about a minute (the oscillatory DNS: 6.4e8 RK4 steps).

set -eu

if [ $# -ne 1 ]; then
  echo "usage: $0 BUILD_DIR" >&2
  exit 2
fi
build=$1
outdir=$(cd "$(dirname "$0")" && pwd)
diss=$build/examples/ode/dissipative
osc=$build/examples/ode/oscillatory
oref=$build/tools/oscillatory_reference
torus=$build/tools/torus_sampling
. "$outdir/../../tools/script_common.sh"
require_built "$diss" "$osc" "$oref" "$torus"
require_gnuplot
set_mpiexec
make_workdir vshmm-figures

run() { # run NAME EXE OPTIONS...: stdout to $tmp/NAME.out; stop on failure
  name=$1
  exe=$2
  shift 2
  echo "  $name: $(basename "$exe") $*"
  # shellcheck disable=SC2086
  if ! $MPIEXEC "$exe" "$@" > "$tmp/$name.out" 2> "$tmp/$name.err"; then
    echo "$0: the $name run failed:" >&2
    cat "$tmp/$name.out" "$tmp/$name.err" >&2
    exit 1
  fi
}

# ---------------------------------------------------------------------------------------------
echo "1. dissipative example (eps = 1e-2, x0 = (5,-10,5))"
vs="-ts_type vshmm -ts_dt 0.1 -ts_vshmm_micro_dt 1e-4 -ts_vshmm_savings_factors 100,10"
run diss_dns "$diss" -ts_type rk -ts_rk_type 4 -ts_dt 1e-6 -slow_csv "$tmp/diss_dns.csv" -slow_csv_stride 1000
run diss_avg "$diss" -mode averaged -ts_type rk -ts_rk_type 4 -ts_dt 1e-2 -slow_csv "$tmp/diss_avg.csv"
# shellcheck disable=SC2086
run diss_var "$diss" $vs -slow_csv "$tmp/diss_var.csv"
# shellcheck disable=SC2086
run diss_const "$diss" $vs -ts_vshmm_kernel constant -slow_csv "$tmp/diss_const.csv"

gnuplot <<EOF
set datafile separator ","
set key top right box opaque
set grid
set xlabel "t"
set ylabel "{/Symbol x}"
set xrange [0:2]
do for [fmt in "png svg"] {
  if (fmt eq "png") { set terminal pngcairo size 1300,520 font "sans,12" } else { set terminal svg size 1300,520 font "sans,12" dynamic }
  set output "$outdir/dissipative.".fmt
  set multiplot layout 1,2 title "Dissipative example, {/Symbol e} = 10^{-2}, ({/Symbol x},{/Symbol h},{/Symbol z})(0) = (5,-10,5)"
  set title "(a) DNS and the averaged equation"
  plot "$tmp/diss_dns.csv" every ::1 using 1:2 with lines lw 2 lc rgb "#1f4e9c" title "DNS (RK4, dt = 10^{-6})", \
       "$tmp/diss_avg.csv" every ::1 using 1:2 with lines lw 2 dt 2 lc rgb "#2ca02c" title "averaged equation (RK4, dt = 10^{-2})"
  set title "(b) DNS and VSHMM ({/Symbol a} = 100, 10; {/Symbol d}t = 10^{-4}; {/Symbol D}T = 0.1)"
  plot "$tmp/diss_dns.csv" every ::1 using 1:2 with lines lw 2 lc rgb "#1f4e9c" title "DNS", \
       "$tmp/diss_var.csv" every ::1 using 1:2 with linespoints lw 1.5 pt 7 ps 0.8 lc rgb "#2ca02c" title "VSHMM, variable steps (cosine kernel)", \
       "$tmp/diss_const.csv" every ::1 using 1:2 with linespoints lw 1.5 pt 5 ps 0.8 lc rgb "#d62728" title "VSHMM, constant steps"
  unset multiplot
  unset output
}
EOF

# ---------------------------------------------------------------------------------------------
echo "2. oscillatory example (eps = 1e-3, x0 = (1,0.5,0,0.5))"
# DNS: RK4 with dt = 1.25e-8 (error < 9e-5 in I1, I2 on [0,8]; docs/ode-experiments.md), by the
# plain-C++ reference tool, which agrees with `oscillatory -ts_type rk -ts_rk_type 4` to ~1e-7.
echo "  osc_dns: $(basename "$oref") --dt 1.25e-8 --tmax 8 (about 20 s)"
"$oref" --dt 1.25e-8 --tmax 8 --print 0.8 --csv "$tmp/osc_dns.csv" --csv-every 0.005 > "$tmp/osc_dns.out"
ov="-ts_type vshmm -ts_dt 0.8 -ts_max_time 8 -ts_vshmm_micro_dt 1e-7"
for a in 68200,330 2000,33; do
  for k in cosine constant; do
    # shellcheck disable=SC2086
    run "osc_${a%%,*}_$k" "$osc" $ov -ts_vshmm_savings_factors $a -ts_vshmm_kernel $k -slow_csv "$tmp/osc_${a%%,*}_$k.csv"
  done
done

gnuplot <<EOF
set datafile separator ","
set key top left Left reverse box opaque width 1 font ",10"
set grid
set xlabel "t"
set xrange [0:8]
set yrange [0:4]
dns = "$tmp/osc_dns.csv"
do for [fmt in "png svg"] {
  if (fmt eq "png") { set terminal pngcairo size 1300,1000 font "sans,12" } else { set terminal svg size 1300,1000 font "sans,12" dynamic }
  set output "$outdir/oscillatory.".fmt
  set multiplot layout 2,2 title "Resonant oscillators, {/Symbol e} = 10^{-3}, (x_1,x_2,y_1,y_2)(0) = (1,0.5,0,0.5); VSHMM {/Symbol d}t = 10^{-7}, {/Symbol D}T = 0.8"
  do for [a in "68200 2000"] {
    lab = (a eq "68200") ? "{/Symbol a} = 68200, 330 (the paper's)" : "{/Symbol a} = 2000, 33"
    do for [k in "constant cosine"] {
      set title ((k eq "constant") ? "constant steps, " : "variable steps (cosine kernel), ").lab
      f = "$tmp/osc_".a."_".k.".csv"
      plot dns every ::1 using 1:2 with lines lw 1.5 lc rgb "#1f4e9c" title "I_1 DNS", \
           dns every ::1 using 1:3 with lines lw 1.5 lc rgb "#ff7f0e" title "I_2 DNS", \
           f every ::1 using 1:2 with linespoints lw 1.5 dt 2 pt 7 ps 1 lc rgb "#2ca02c" title "I_1 VSHMM", \
           f every ::1 using 1:3 with linespoints lw 1.5 dt 2 pt 5 ps 1 lc rgb "#d62728" title "I_2 VSHMM"
    }
  }
  unset multiplot
  unset output
}
EOF

# ---------------------------------------------------------------------------------------------
echo "3. torus sampling (60 points, beta = sqrt(1.01))"
echo "  torus: $(basename "$torus")"
"$torus" > "$tmp/torus.dat"
dc=$(sed -n 's/^# star discrepancy constant \([0-9.]*\) variable \([0-9.]*\).*/\1/p' "$tmp/torus.dat")
dv=$(sed -n 's/^# star discrepancy constant \([0-9.]*\) variable \([0-9.]*\).*/\2/p' "$tmp/torus.dat")
echo "  star discrepancy: constant steps $dc, variable steps $dv"

gnuplot <<EOF
set key off
set grid
set size ratio -1
dat = "$tmp/torus.dat"
do for [fmt in "png svg"] {
  if (fmt eq "png") { set terminal pngcairo size 1100,1100 font "sans,12" } else { set terminal svg size 1100,1100 font "sans,12" dynamic }
  set output "$outdir/torus.".fmt
  set multiplot layout 2,2 title "60 sampling points of the phases ({/Symbol h}, {/Symbol z}) of two periodic fast variables, {/Symbol b} = h_2/{/Symbol d}t = sqrt(1.01); variable steps: cosine kernel"
  do for [s = 0:1] {
    name = (s == 0) ? "constant" : "variable"
    disc = (s == 0) ? $dc : $dv
    set title sprintf("(%s) %s steps in the plane (copies of the torus)", (s == 0) ? "a" : "c", name)
    set xlabel "{/Symbol h} (periods)"
    set ylabel "{/Symbol z} (periods)"
    set xrange [0:12]
    set yrange [0:12]
    set xtics 1
    set ytics 1
    plot dat index s using 2:3 with linespoints pt 7 ps 0.7 lc rgb (s == 0 ? "#d62728" : "#2ca02c")
    set title sprintf("(%s) %s steps on the torus, D* = %.3f", (s == 0) ? "b" : "d", name, disc)
    set xlabel "{/Symbol h} mod 1"
    set ylabel "{/Symbol z} mod 1"
    set xrange [0:1]
    set yrange [0:1]
    set xtics 0.2
    set ytics 0.2
    plot dat index s using 4:5 with points pt 7 ps 1 lc rgb (s == 0 ? "#d62728" : "#2ca02c")
  }
  unset multiplot
  unset output
}
EOF

echo "Figures written to $outdir: dissipative, oscillatory, torus (.png, .svg)"
