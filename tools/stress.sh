#!/bin/sh
# shellcheck disable=SC2046 # "set -- $(maxerr ...)" and $(vshmm_report ...) split on purpose
# stress.sh - the long stress runs of TSVSHMM (issue #5, "Hard cases stay numerically stable")
#
# Usage: tools/stress.sh BUILD_DIR
#
# Runs the long versions of the stress suite (examples/stress/stress.cmake has the short ones)
# with the parameter rules of docs/stress.md and prints one markdown table: for each run the
# largest error of the slow variable over ALL sampled times against its reference, the
# tolerance, the split evaluations and wall time of TSVSHMM, and the cost of a DNS.
#   1. dissipative.c, eps = 1e-2, 5e-3, 1e-3, 1e-4, 1e-5, t in [0, 2], xi every 0.1:
#      rule A (mean h_1 = 0.2 eps, tolerance 3 eps) and rule B (mean h_1 = 2e-3, tolerance
#      3e-2), against the averaged equation and, for eps >= 1e-3, an RK4 DNS (dt = eps^2/4);
#   2. chain.c, e = 1e-2 with 2..6 scales, e = 1e-3 with 3..5, e = 1e-4 with 3..4, t in [0, 10],
#      x0 every 0.1 against the DNS of the 2-scale chain (exact for every number of scales;
#      tolerance e), and the DNS of the chain itself where it is affordable (<= 4e7 evaluations);
#   3. oscillatory.c (if built), eps = 1e-3 and 1e-4, t in [0, 50], I1 and I2 every 0.5 (0.8 for
#      the paper's DeltaT) against the averaged (Lotka-Volterra) equations and, for eps = 1e-3, a
#      converged DNS by tools/oscillatory_reference (dt = 1.25e-8: 4e9 RK4 steps, ~2 minutes);
#      the drift of the Lotka-Volterra invariant V = I1 - 2 ln I1 + 1.5 I2 - 0.5 ln I2.
# DNS costs that are not affordable are estimated (marked ~) from the step count and the time
# per evaluation of the last DNS of the same problem that was run (PETSc TSRK 4).
#
# Environment: STRESS_WORKDIR (default: a new directory /tmp/vshmm-stress.XXXXXX; it keeps every
# output and CSV file), STRESS_NO_OSC_DNS=1 skips the 2-minute oscillatory DNS, STRESS_NICE
# (default "nice -n 10"). Run time: about 3.5 minutes on one core (2 of them in DNS runs).
# Exit status: 0 if every required run reached its final time within its tolerance, else 1.
# (The rows of the paper's oscillatory parameters, P5 and P8, are reported but not required.)

set -u

if [ $# -ne 1 ] || [ ! -d "$1" ]; then
  echo "usage: $0 BUILD_DIR" >&2
  exit 2
fi
B=$(cd "$1" && pwd)
DISS=$B/examples/ode/dissipative
CHAIN=$B/examples/stress/chain
OSC=$B/examples/ode/oscillatory
OREF=$B/tools/oscillatory_reference
for p in "$DISS" "$CHAIN"; do
  if [ ! -x "$p" ]; then
    echo "$0: $p is missing: build the examples first (cmake --build $1)" >&2
    exit 2
  fi
done
W=${STRESS_WORKDIR:-$(mktemp -d /tmp/vshmm-stress.XXXXXX)}
mkdir -p "$W" || exit 2
NICE=${STRESS_NICE:-nice -n 10}
T0=$(date +%s)
status=0
TABLE=$W/table.md
: > "$TABLE"

log() { echo "$*" >&2; }

# run NAME TMAX CMD... : run a program (niced), stdout in NAME.out, stderr in NAME.err. Returns 0
# if it exited with 0 and its "final t" line is TMAX; otherwise sets $why.
run() {
  rn=$1
  rt=$2
  shift 2
  log "  $rn: $*"
  why=""
  rc=0
  # shellcheck disable=SC2086 # $NICE is a command with arguments
  $NICE "$@" > "$W/$rn.out" 2> "$W/$rn.err" || rc=$?
  if [ $rc != 0 ]; then
    why="exit status $rc: $(grep -m1 -E 'ERROR: [A-Z]' "$W/$rn.err" | sed 's/.*ERROR: //' | cut -c1-160)"
  else
    reached=$(awk '$1 == "final" && $2 == "t" { print $3 }' "$W/$rn.out")
    if ! awk -v a="$reached" -v b="$rt" 'BEGIN { exit !(a != "" && a - b < 1e-9 * b && b - a < 1e-9 * b) }'; then
      why="stopped at t = ${reached:-?}"
      [ -f "$W/$rn.warnings" ] && why="$why: $(grep -m1 -o 'produced Inf or NaN at t = [0-9.e+-]*' "$W/$rn.warnings")"
    fi
  fi
  if [ -n "$why" ]; then
    log "  $rn FAILED: $why"
    return 1
  fi
  return 0
}

# value NAME KEY: the number after KEY in NAME.out (rhs_evaluations, wall_time)
value() { awk -v k="$2" '$1 == k { print $2 }' "$W/$1.out"; }

# vshmm_report NAME: the options of a TSVSHMM run NAME: -ts_view prints the statistics
# (TSVSHMMGetStatistics()) in NAME.out, the library's warnings go to NAME.warnings (which names
# the split and time of an Inf or NaN that stopped the solve)
vshmm_report() { echo "-ts_view -ts_vshmm_warnings_viewer ascii:$W/$1.warnings"; }

# warned NAME: " (stability warning)" if the statistics of NAME count stability warnings (the
# "stability check: ..., N warnings" line of -ts_view), else nothing
warned() {
  awk '/stability check:/ && $NF == "warnings" && $(NF - 1) > 0 { w = 1 } END { if (w) printf " (stability warning)" }' "$W/$1.out"
}

# maxerr REF.csv RUN.csv COL: the largest |RUN - REF| in column COL over the times of RUN.csv
# (matched to 4 decimals) and the number of times of RUN.csv missing from REF.csv.
maxerr() {
  awk -F, -v col="$3" '
    FNR == 1 { next }
    NR == FNR { ref[sprintf("%.4f", $1)] = $col; next }
    { k = sprintf("%.4f", $1)
      if (!(k in ref)) { miss++; next }
      d = $col - ref[k]; if (d < 0) d = -d
      if (d != d || $col ~ /nan|inf/) d = 1e300
      if (d > m) m = d }
    END { printf "%.2e %d\n", m + 0, miss + 0 }' "$1" "$2"
}

# lvref OUT.csv TMAX EVERY: the averaged equations of the oscillatory example, the Lotka-Volterra
# system I1' = I1/2 - 3/2 I1 I2, I2' = -2 I2 + I1 I2, I(0) = (1, 0.5), by RK4 with step 1e-3
# (converged to 1e-12), written at the multiples of EVERY.
lvref() {
  awk -v tmax="$2" -v every="$3" 'function f1(a, b) { return 0.5 * a - 1.5 * a * b }
    function f2(a, b) { return -2 * b + a * b }
    BEGIN {
      h = 1e-3; a = 1; b = 0.5; n = int(tmax / h + 0.5); m = int(every / h + 0.5)
      print "t,I1,I2"; printf "0,%.16e,%.16e\n", a, b
      for (s = 1; s <= n; s++) {
        k1a = f1(a, b); k1b = f2(a, b)
        k2a = f1(a + h / 2 * k1a, b + h / 2 * k1b); k2b = f2(a + h / 2 * k1a, b + h / 2 * k1b)
        k3a = f1(a + h / 2 * k2a, b + h / 2 * k2b); k3b = f2(a + h / 2 * k2a, b + h / 2 * k2b)
        k4a = f1(a + h * k3a, b + h * k3b); k4b = f2(a + h * k3a, b + h * k3b)
        a += h / 6 * (k1a + 2 * k2a + 2 * k3a + k4a); b += h / 6 * (k1b + 2 * k2b + 2 * k3b + k4b)
        if (s % m == 0) printf "%.10g,%.16e,%.16e\n", s * h, a, b
      }
    }' > "$1"
}

# vdrift RUN.csv: the largest |V(I1, I2) - V(1, 0.5)| over the rows (1e300 if I1 or I2 <= 0)
vdrift() {
  awk -F, 'function V(a, b) { return a - 2 * log(a) + 1.5 * b - 0.5 * log(b) }
    FNR == 1 { v0 = V(1, 0.5); next }
    { if (!($2 > 0) || !($3 > 0)) { m = 1e300; next }
      d = V($2 + 0, $3 + 0) - v0; if (d < 0) d = -d; if (d > m) m = d }
    END { printf "%.2e\n", m + 0 }' "$1"
}

# check ERR TOL: "yes" if ERR <= TOL, else "NO"
check() {
  if awk -v e="$1" -v t="$2" 'BEGIN { exit !(e + 0 <= t + 0) }'; then echo yes; else echo NO; fi
}

# g EXPR: evaluate an awk expression, print with %.6g; g3: with %.3g
g() { awk "BEGIN { printf \"%.6g\", $1 }"; }
g3() { awk "BEGIN { printf \"%.3g\", $1 }"; }

# dnscost EVALS WALL: "EVALS (WALL s)"; with WALL empty, an estimate "~EVALS (~T s)" from the
# time per evaluation $tpe of the last DNS run (set by dnsrun)
tpe=""
dnscost() {
  if [ -n "$2" ]; then
    echo "$(g "$1") ($(g3 "$2") s)"
  elif [ -n "$tpe" ]; then
    echo "~$(g3 "$1") (~$(g3 "$1 * $tpe") s)"
  else
    echo "~$(g3 "$1")"
  fi
}

# ratio "DNS_COST" EVALS: DNS evaluations / EVALS, with the "~" of an estimate
ratio() {
  echo "$1" | awk -v ev="$2" '{ s = $1; t = ""; if (substr(s, 1, 1) == "~") { t = "~"; s = substr(s, 2) }
    if (s + 0 > 0 && ev + 0 > 0) printf "%s%.3g\n", t, s / ev; else print "-" }'
}

row() { echo "| $* |" >> "$TABLE"; }

row "problem | eps or e, scales | rule: dt; alpha (slowest first) | max error over all samples (reference) | tolerance | ok | split evaluations | wall time [s] | DNS evaluations (wall time) | ratio"
row "---|---|---|---|---|---|---|---|---|---"

# --- 1. dissipative.c ------------------------------------------------------------------------
log "== dissipative.c, eps = 1e-2 ... 1e-5 (work directory $W)"
run diss_avg 2 "$DISS" -mode averaged -ts_type rk -ts_rk_type 4 -ts_dt 1e-3 -slow_csv "$W/diss_avg.csv" -slow_csv_stride 100 || status=1
for eps in 1e-2 5e-3 1e-3 1e-4 1e-5; do
  dt=$(g "$eps * $eps")
  ddt=$(g "$eps * $eps / 4") # DNS: RK4, stable to 2.78 eps^2, converged to ~1e-8 in xi
  dnsref=""
  if awk -v e="$eps" 'BEGIN { exit !(e >= 1e-3) }'; then
    if run "diss_dns_$eps" 2 "$DISS" -eps "$eps" -ts_type rk -ts_rk_type 4 -ts_dt "$ddt" -slow_csv "$W/diss_dns_$eps.csv" -slow_csv_stride "$(g "int(0.1 / $ddt + 0.5)")"; then
      dnsref=$W/diss_dns_$eps.csv
      tpe=$(g "$(value "diss_dns_$eps" wall_time) / $(value "diss_dns_$eps" rhs_evaluations)")
      dns=$(dnscost "$(value "diss_dns_$eps" rhs_evaluations)" "$(value "diss_dns_$eps" wall_time)")
    else
      status=1
      dns="failed"
    fi
  else
    dns=$(dnscost "$(g "4 * 2 / $ddt")" "")
  fi
  for rule in A B; do
    if [ $rule = A ]; then
      a1=$(g "0.2 / $eps"); tol=$(g "3 * $eps")
    else
      a1=$(g "2e-3 / ($eps * $eps)"); tol=3e-2
    fi
    a2=$(g "0.05 / $eps")
    name=diss_${rule}_$eps
    if run "$name" 2 "$DISS" -eps "$eps" -ts_type vshmm -ts_dt 0.1 -ts_vshmm_micro_dt "$dt" -ts_vshmm_savings_factors "$a1,$a2" \
      -ts_vshmm_check_stability_interval 1 -ts_error_if_step_fails false -slow_csv "$W/$name.csv" $(vshmm_report "$name"); then
      set -- $(maxerr "$W/diss_avg.csv" "$W/$name.csv" 2)
      err="$1 (averaged)"
      ok=$(check "$1" "$tol")
      [ "$2" = 0 ] || ok="NO ($2 unmatched times)"
      if [ -n "$dnsref" ]; then
        set -- $(maxerr "$dnsref" "$W/$name.csv" 2)
        err="$err, $1 (DNS)"
      fi
      ev=$(value "$name" rhs_evaluations)
      wall=$(g3 "$(value "$name" wall_time)")
      rat=$(ratio "$dns" "$ev")
    else
      err="failed: $why"; ok=NO; ev=-; wall=-; rat=-
    fi
    ok="$ok$(warned "$name")"
    [ "$ok" = yes ] || status=1
    row "dissipative, rule $rule, t = 2 | eps = $eps | $dt; $a1, $a2 | $err | $tol | $ok | $ev | $wall | $dns | $rat"
  done
done

# --- 2. chain.c ------------------------------------------------------------------------------
log "== chain.c, 2..6 scales"
for e in 1e-2 1e-3 1e-4; do
  # the exact reference for every number of scales: the DNS of the 2-scale chain (RK4, dt = e/100)
  rdt=$(g "$e / 100")
  run "chain_ref_$e" 10 "$CHAIN" -scales 2 -e "$e" -ts_type rk -ts_rk_type 4 -ts_dt "$rdt" -ts_max_time 10 \
    -slow_csv "$W/chain_ref_$e.csv" -slow_csv_stride "$(g "int(0.1 / $rdt + 0.5)")" || status=1
  case $e in
    1e-2) scales="2 3 4 5 6" ;;
    1e-3) scales="3 4 5" ;;
    *) scales="3 4" ;;
  esac
  for n in $scales; do
    K=$((n - 1))
    dt=$(g "$e ^ $K")
    al=$(awk -v e="$e" -v K="$K" 'BEGIN { eK = e ^ K; printf "%.6g", 0.5 * e / eK; for (j = 2; j <= K; j++) printf ",%.6g", e ^ (j - 1) / eK }')
    name=chain_${n}_$e
    dnsevals=$(g "4 * 10 / $dt") # DNS: RK4 with dt = e^K, run if affordable
    if awk -v s="$dnsevals" 'BEGIN { exit !(s <= 4e7) }'; then
      if run "${name}_dns" 10 "$CHAIN" -scales "$n" -e "$e" -ts_type rk -ts_rk_type 4 -ts_dt "$dt" -ts_max_time 10 -print_interval 10; then
        tpe=$(g "$(value "${name}_dns" wall_time) / $(value "${name}_dns" rhs_evaluations)")
        dns=$(dnscost "$(value "${name}_dns" rhs_evaluations)" "$(value "${name}_dns" wall_time)")
      else
        dns=failed; status=1
      fi
    else
      dns=$(dnscost "$dnsevals" "")
    fi
    if run "$name" 10 "$CHAIN" -scales "$n" -e "$e" -ts_type vshmm -ts_dt 0.1 -ts_max_time 10 -ts_vshmm_micro_dt "$dt" -ts_vshmm_savings_factors "$al" \
      -ts_vshmm_check_stability_interval 1 -ts_error_if_step_fails false -slow_csv "$W/$name.csv" $(vshmm_report "$name"); then
      set -- $(maxerr "$W/chain_ref_$e.csv" "$W/$name.csv" 2)
      err="$1 (DNS); max abs state $(awk '$1 == "max_abs_state" { print $2 }' "$W/$name.out")"
      ok=$(check "$1" "$e")
      [ "$2" = 0 ] || ok="NO ($2 unmatched times)"
      ev=$(value "$name" rhs_evaluations)
      wall=$(g3 "$(value "$name" wall_time)")
      rat=$(ratio "$dns" "$ev")
    else
      err="failed: $why"; ok=NO; ev=-; wall=-; rat=-
    fi
    ok="$ok$(warned "$name")"
    [ "$ok" = yes ] || status=1
    row "chain, t = 10 | e = $e, $n scales | $dt; $al | $err | $e | $ok | $ev | $wall | $dns | $rat"
  done
done

# --- 3. oscillatory.c ------------------------------------------------------------------------
if [ -x "$OSC" ]; then
  log "== oscillatory.c, eps = 1e-3 and 1e-4, t = 50"
  lvref "$W/osc_lv.csv" 50 0.1
  oscdns=""
  if [ "${STRESS_NO_OSC_DNS:-0}" != 1 ] && [ -x "$OREF" ]; then
    if run osc_dns_1e-3 50 "$OREF" --eps 1e-3 --dt 1.25e-8 --tmax 50 --print 10 --csv "$W/osc_dns_1e-3.csv" --csv-every 0.1; then
      oscdns=$W/osc_dns_1e-3.csv
      set -- $(maxerr "$W/osc_lv.csv" "$oscdns" 2)
      e1=$1
      set -- $(maxerr "$W/osc_lv.csv" "$oscdns" 3)
      row "oscillatory DNS vs averaged, t = 50 | eps = 1e-3 | plain RK4, 1.25e-8 | I1 $e1, I2 $1; V drift $(vdrift "$oscdns") | - | - | $(g "$(value osc_dns_1e-3 rhs_evaluations)") | $(g3 "$(value osc_dns_1e-3 wall_time)") | - | -"
    else
      status=1
    fi
  fi
  for eps in 1e-3 1e-4; do
    dt=$(g "0.1 * $eps * $eps")
    tpe="" # the PETSc DNS times above do not apply to this 4-component system
    dns=$(dnscost "$(g "4 * 50 / (1.25e-8 * ($eps / 1e-3) ^ 2)")" "")
    [ "$eps" = 1e-3 ] && [ -n "$oscdns" ] && dns="$(g "$(value osc_dns_1e-3 rhs_evaluations)") ($(g3 "$(value osc_dns_1e-3 wall_time)") s, plain C)"
    for rule in O P5 P8; do
      case $rule in
        O) a1=$(g "2e-4 / $dt"); a2=$(g "0.1 / $eps"); DT=0.5 ;;
        P5) a1=$(g "6.82e-3 / $dt"); a2=$(g "0.33 / $eps"); DT=0.5 ;;
        *) a1=$(g "6.82e-3 / $dt"); a2=$(g "0.33 / $eps"); DT=0.8 ;;
      esac
      tol=5e-2
      name=osc_${rule}_$eps
      if run "$name" 50 "$OSC" -eps "$eps" -ts_type vshmm -ts_dt "$DT" -ts_max_time 50 -ts_vshmm_micro_dt "$dt" -ts_vshmm_savings_factors "$a1,$a2" \
        -ts_vshmm_check_stability_interval 1 -ts_error_if_step_fails false -slow_csv "$W/$name.csv" $(vshmm_report "$name"); then
        set -- $(maxerr "$W/osc_lv.csv" "$W/$name.csv" 2)
        e1=$1
        set -- $(maxerr "$W/osc_lv.csv" "$W/$name.csv" 3)
        e2=$1
        err="I1 $e1, I2 $e2 (averaged)"
        ok=$(check "$(awk -v a="$e1" -v b="$e2" 'BEGIN { print (a > b ? a : b) }')" "$tol")
        if [ "$eps" = 1e-3 ] && [ -n "$oscdns" ]; then
          set -- $(maxerr "$oscdns" "$W/$name.csv" 2)
          e1=$1
          set -- $(maxerr "$oscdns" "$W/$name.csv" 3)
          err="$err; I1 $e1, I2 $1 (DNS)"
        fi
        err="$err; V drift $(vdrift "$W/$name.csv")"
        ev=$(value "$name" rhs_evaluations)
        wall=$(g3 "$(value "$name" wall_time)")
        rat=$(ratio "$dns" "$ev")
      else
        err="failed: $why"; ok=NO; ev=-; wall=-; rat=-
      fi
      if [ "$rule" = O ]; then
        [ "$ok" = yes ] || status=1
      else
        ok="$ok (paper's alpha; not required)"
      fi
      row "oscillatory, rule $rule, t = 50 | eps = $eps | $dt; $a1, $a2; DeltaT = $DT | $err | $tol | $ok | $ev | $wall | $dns | $rat"
    done
  done
else
  log "== $OSC not built: oscillatory runs skipped"
  row "oscillatory | - | - | not run: $OSC not built | - | - | - | - | - | -"
fi

T1=$(date +%s)
echo
cat "$TABLE"
echo
echo "total run time $((T1 - T0)) s; outputs and CSV files in $W"
if [ $status = 0 ]; then
  echo "all required runs finished within their tolerances"
else
  echo "SOME REQUIRED RUNS FAILED OR EXCEEDED THEIR TOLERANCE"
fi
exit $status
