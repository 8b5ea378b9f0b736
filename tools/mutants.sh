#!/bin/sh
# mutants.sh - mutation check of the test suite (make mutants; docs/testing.md).
#
# Usage: sh tools/mutants.sh [LIST]     (LIST: tools/mutants.txt)
#
# Copies the source tree (git's tracked files, as they are in the working tree) to a work
# directory, configures a build there once, checks that the unmutated copy passes, and for each
# one-line mutation of LIST: applies it to the COPY (the working tree is never touched), rebuilds
# incrementally and runs the tests in two stages, stopping at the first failing test
# (ctest --stop-on-failure):
#   1. the one-rank GoogleTest programs vshmm_core_tests, vshmm_spectral_tests, vshmm_ts_tests
#      (a few seconds; they kill most mutants);
#   2. everything else except the memcheck, install and dll labels (two-rank unit tests, example,
#      stress and spectral runs; about two minutes on one core).
# Then it puts the file back. Outcomes:
#   KILLED     a test failed or timed out (its name is given), or the mutant does not build;
#   SURVIVED   every test passed: a test is missing;
#   EQUIVALENT every test passed and LIST gives the reason why no test can kill it;
#   NOT FOUND  the original text is not in exactly one line of the file (or the file is gone): the
#              list is out of date (the script says where else the text occurs); not run, not
#              counted in the kill rate, and the exit status is non-zero.
# Prints one line per mutant, then a summary table and the kill rate; the report is kept in
# WORK/report.txt.
#
# Environment: MUTANTS_WORK (work directory, default ${TMPDIR:-/tmp}/petscvshmm-mutants, kept
# between runs so that the first build is reused), JOBS (build and ctest jobs, 1),
# FAST_TIMEOUT (seconds for stage 1, 120: it takes about 3 s, so a mutant that makes a test hang
# is caught early), MUTANT_TIMEOUT (seconds for stage 2, 900), TEST_TIMEOUT (seconds per test
# without its own TIMEOUT property, 300),
# MUTANTS_ONLY (run only the mutants with these numbers, e.g. "1 5"; numbers count the mutant
# lines of LIST from 1). Runs under nice. Exit status 0 when every mutant was applied and every
# one not marked equivalent was killed.
set -eu

here=$(cd "$(dirname "$0")/.." && pwd)
list=${1:-$here/tools/mutants.txt}
work=${MUTANTS_WORK:-${TMPDIR:-/tmp}/petscvshmm-mutants}
jobs=${JOBS:-1}
limit=${MUTANT_TIMEOUT:-900}
fast_limit=${FAST_TIMEOUT:-120}
test_limit=${TEST_TIMEOUT:-300}
src=$work/src
build=$work/build
report=$work/report.txt
fast='^vshmm_(core|spectral|ts)_tests$'

[ -r "$list" ] || { echo "$0: cannot read $list" >&2; exit 2; }
command -v git >/dev/null 2>&1 || { echo "$0: needs git" >&2; exit 2; }
command -v perl >/dev/null 2>&1 || { echo "$0: needs perl" >&2; exit 2; }
case $list in /*) ;; *) list=$(pwd)/$list ;; esac

# The tracked files, copied into $src where their content differs from what is there (a copy
# takes the current time, so make rebuilds it); files whose content is the same keep their time in
# $src, so the build stays incremental. (A fresh copy that kept the working tree's times let a file
# edited in the tree between two runs look older than its object, where a mutant of the same file
# in the first run had been built after the edit: the second run tested the code before the edit.)
# Files no longer tracked are removed.
mkdir -p "$work" "$src"
stage="$work/stage"
rm -rf "$stage"
mkdir -p "$stage"
(cd "$here" && git ls-files -z | xargs -0 tar cf - ) | (cd "$stage" && tar xf -)
(cd "$stage" && find . -type f -print) | while IFS= read -r f; do
  if ! cmp -s "$stage/$f" "$src/$f"; then
    mkdir -p "$src/$(dirname "$f")"
    cp "$stage/$f" "$src/$f"
  fi
done
(cd "$src" && find . -type f -print) | while IFS= read -r f; do [ -e "$stage/$f" ] || rm -f "$src/$f"; done
rm -rf "$stage"
if [ -f "$work/mutated" ]; then
  f=$(cat "$work/mutated")
  [ -f "$src/$f" ] && touch "$src/$f"
  rm -f "$work/mutated"
fi

# run_tests: 0 when every test passes; otherwise 1 and the first failing test in $work/failed.
run_tests() {
  rm -f "$work/failed"
  for stage in 1 2; do
    if [ $stage = 1 ]; then set -- -R "$fast"; t=$fast_limit; else set -- -E "$fast" -LE 'memcheck|install|dll'; t=$limit; fi
    if ! timeout "$t" nice -n 10 ctest --test-dir "$build" -j "$jobs" --timeout "$test_limit" --stop-on-failure --output-on-failure "$@" >"$work/ctest.log" 2>&1 </dev/null; then
      # ctest's closing list: "<tab> 87 - vshmm_ts_tests_np2 (Failed)"
      sed -n -E 's/^[[:space:]]*[0-9]+ - ([^ ]+) \((.*)\)$/\1 (\2)/p' "$work/ctest.log" | head -n 1 >"$work/failed"
      # and the first failing GoogleTest case, if any: "[  FAILED  ] VSHMMFaults.X (12 ms)"
      gcase=$(sed -E 's/\x1b\[[0-9;]*m//g' "$work/ctest.log" | sed -n -E 's/^\[  FAILED  \] ([A-Za-z_][A-Za-z0-9_]*\.[A-Za-z0-9_/.]+)( \(.*|, .*)$/\1/p' | head -n 1)
      if [ -n "$gcase" ] && [ -s "$work/failed" ]; then printf '%s: %s\n' "$(cat "$work/failed")" "$gcase" >"$work/failed"; fi
      if [ ! -s "$work/failed" ]; then # stopped by the time limit: name the test that was running
        running=$(sed -n -E 's/^ *Start +[0-9]+: ([^ ]+).*/\1/p' "$work/ctest.log" | tail -n 1)
        echo "${running:-ctest} (the tests of stage $stage exceeded $t s)" >"$work/failed"
      fi
      return 1
    fi
  done
  return 0
}

start_all=$(date +%s)
echo "mutants.sh: work directory $work; configuring and building the unmutated copy"
if [ ! -f "$build/CMakeCache.txt" ]; then
  nice -n 10 cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=Release >"$work/configure.log" 2>&1 || { echo "$0: configure failed, see $work/configure.log" >&2; exit 2; }
fi
nice -n 10 cmake --build "$build" -j "$jobs" >"$work/build.log" 2>&1 || { echo "$0: the unmutated copy does not build, see $work/build.log" >&2; exit 2; }
if ! run_tests; then
  echo "$0: the unmutated copy fails its tests ($(cat "$work/failed")): fix that first" >&2
  exit 2
fi
echo "mutants.sh: the unmutated copy passes ($(($(date +%s) - start_all)) s)"

: >"$report"
: >"$work/summary"
total=0 killed=0 survived=0 equivalent=0 notfound=0 n=0
# LIST lines: file @@ original @@ mutated @@ description [@@ equivalent: reason]
grep -v -e '^#' -e '^[[:space:]]*$' "$list" >"$work/list"
while IFS= read -r line; do
  n=$((n + 1))
  if [ -n "${MUTANTS_ONLY:-}" ] && ! printf ' %s ' "$MUTANTS_ONLY" | grep -q " $n "; then continue; fi
  file=$(printf '%s\n' "$line" | awk -F' @@ ' '{print $1}')
  orig=$(printf '%s\n' "$line" | awk -F' @@ ' '{print $2}')
  desc=$(printf '%s\n' "$line" | awk -F' @@ ' '{print $4}')
  equiv=$(printf '%s\n' "$line" | awk -F' @@ ' '{print $5}')
  total=$((total + 1))
  start=$(date +%s)
  # Apply: the original text must be in exactly one line of the file.
  cp "$src/$file" "$work/original" 2>/dev/null || : >"$work/original"
  echo "$file" >"$work/mutated"
  if ! MUT_LINE=$line perl -e '
      my ($f, $o, $m) = split / \@\@ /, $ENV{MUT_LINE};
      open(my $in, "<", $ARGV[0]) or die "file not found\n";
      my @l = <$in>; close $in;
      my @hit = grep { index($l[$_], $o) >= 0 } 0 .. $#l;
      die "pattern not found\n" unless @hit;
      die "pattern found in " . scalar(@hit) . " lines, must be one\n" unless @hit == 1;
      substr($l[$hit[0]], index($l[$hit[0]], $o), length $o) = $m;
      open(my $out, ">", $ARGV[0]) or die; print $out @l; close $out;' "$src/$file" 2>"$work/apply.log"; then
    rm -f "$work/mutated"
    why=$(cat "$work/apply.log")
    # Where the text went (e.g. after code moved between files): a hint for updating LIST.
    elsewhere=$(cd "$src" && { grep -rlF -e "$orig" src 2>/dev/null || true; } | tr '\n' ' ')
    if [ -n "$elsewhere" ]; then hint="the text is now in: $elsewhere(update $(basename "$list"))"
    else hint="the text is nowhere under src/ (update $(basename "$list"))"; fi
    notfound=$((notfound + 1))
    printf 'mutant %2d NOT FOUND: %s in %s; %s\n    %s: %s\n' "$n" "$why" "$file" "$hint" "$file" "$desc" | tee -a "$report"
    printf '%s\t%s\t%s\t%s\t%s\n' "$n" "NOT FOUND" "-" "$file" "$desc" >>"$work/summary"
    continue
  fi
  if ! nice -n 10 cmake --build "$build" -j "$jobs" >"$work/build.log" 2>&1 </dev/null; then
    result="KILLED" by="does not build"
    killed=$((killed + 1))
  elif ! run_tests; then
    result="KILLED" by=$(cat "$work/failed")
    killed=$((killed + 1))
  else
    survived=$((survived + 1))
    if [ -n "$equiv" ]; then
      result="EQUIVALENT" by="survived; ${equiv#equivalent: }"
      equivalent=$((equivalent + 1))
    else
      result="SURVIVED" by="NOT EQUIVALENT: needs a test"
    fi
  fi
  # Put the file back (a new mtime, so that the next build recompiles it).
  cp "$work/original" "$src/$file"
  touch "$src/$file"
  rm -f "$work/mutated"
  secs=$(($(date +%s) - start))
  printf 'mutant %2d %s (%s) %ss\n    %s: %s\n' "$n" "$result" "$by" "$secs" "$file" "$desc" | tee -a "$report"
  printf '%s\t%s\t%s\t%s\t%s\n' "$n" "$result" "${secs}s" "$file" "$desc" >>"$work/summary"
done <"$work/list"
nice -n 10 cmake --build "$build" -j "$jobs" >"$work/build.log" 2>&1 || true

applied=$((total - notfound))
unexpected=$((survived - equivalent))
rate=$(awk -v k="$killed" -v t="$applied" 'BEGIN { printf "%.0f", t ? 100 * k / t : 0 }')
rate_ne=$(awk -v k="$killed" -v t="$((applied - equivalent))" 'BEGIN { printf "%.0f", t ? 100 * k / t : 0 }')
{
  echo
  echo "summary (#, outcome, time, file, mutation):"
  awk -F'\t' '{ printf "  %3s  %-10s %6s  %-32s %s\n", $1, $2, $3, $4, $5 }' "$work/summary"
  echo "mutants: $total listed, $applied applied: $killed killed, $unexpected survived, $equivalent equivalent (survived, marked in the list); $notfound not found"
  echo "kill rate: $rate% of the applied mutants, $rate_ne% of the applied mutants not marked equivalent"
  echo "time: $(($(date +%s) - start_all)) s"
  if [ "$unexpected" -gt 0 ]; then echo "FAIL: $unexpected mutant(s) not marked equivalent survived: add tests that kill them"; fi
  if [ "$notfound" -gt 0 ]; then echo "FAIL: $notfound mutant(s) could not be applied (pattern not found): update $(basename "$list")"; fi
  if [ "$unexpected" -eq 0 ] && [ "$notfound" -eq 0 ]; then echo "OK: every mutant not marked equivalent was killed"; fi
} | tee -a "$report"
[ "$unexpected" -eq 0 ] && [ "$notfound" -eq 0 ]
