#!/bin/sh
# mutants.sh - mutation check of the test suite (make mutants; docs/testing.md).
#
# Usage: sh tools/mutants.sh [LIST]     (LIST: tools/mutants.txt)
#
# Copies the source tree (git's tracked files) to a work directory, configures a build there
# once, and for each one-line mutation of LIST: applies it to the COPY (the working tree is never
# touched), rebuilds incrementally, runs the test suite (first the label 'unit', then the example,
# stress and spectral runs; memcheck, install and dll tests are left out), stopping at the first
# failure, and restores the file. A mutant is killed when a test fails, the build fails or the
# tests exceed MUTANT_TIMEOUT seconds; it survived when every test passes. Prints one line per
# mutant and the kill rate; the report is kept in WORK/report.txt.
#
# Environment: MUTANTS_WORK (work directory, default ${TMPDIR:-/tmp}/petscvshmm-mutants, kept
# between runs so that the first build is reused), JOBS (build jobs, 1), MUTANT_TIMEOUT (600),
# MUTANTS_ONLY (run only the mutants whose line numbers in LIST's mutant order are given, e.g. "1 5").
# Runs under nice. Exit status 0 when every mutant not listed as equivalent in LIST was killed.
set -eu

here=$(cd "$(dirname "$0")/.." && pwd)
list=${1:-$here/tools/mutants.txt}
work=${MUTANTS_WORK:-${TMPDIR:-/tmp}/petscvshmm-mutants}
jobs=${JOBS:-1}
limit=${MUTANT_TIMEOUT:-600}
src=$work/src
build=$work/build
report=$work/report.txt

[ -r "$list" ] || { echo "$0: cannot read $list" >&2; exit 2; }
command -v git >/dev/null 2>&1 || { echo "$0: needs git" >&2; exit 2; }
command -v perl >/dev/null 2>&1 || { echo "$0: needs perl" >&2; exit 2; }

# A pristine copy of the tracked files (updated from the working tree at every run).
mkdir -p "$src"
(cd "$here" && git ls-files -z | xargs -0 tar cf - ) | (cd "$src" && tar xf - --overwrite)

run_tests() { # exit status of the suite; the first failing test's name in $work/failed
  rm -f "$work/failed"
  for labels in "-L unit" "-LE unit|memcheck|install|dll"; do
    # shellcheck disable=SC2086
    if ! timeout "$limit" nice -n 10 ctest --test-dir "$build" -j1 --stop-on-failure $labels >"$work/ctest.log" 2>&1 </dev/null; then
      grep -m1 -E '\*\*\*(Failed|Timeout|Exception)|\(Failed\)|\(Timeout\)' "$work/ctest.log" | sed -E 's/.*Test +#[0-9]+: ([^ ]+).*/\1/; s/^[[:space:]]*[0-9]+ - ([^ ]+).*/\1/' >"$work/failed" || true
      [ -s "$work/failed" ] || echo "timeout or ctest error" >"$work/failed"
      return 1
    fi
  done
  return 0
}

echo "mutants.sh: work directory $work; configuring and building the unmutated copy"
if [ ! -f "$build/CMakeCache.txt" ]; then
  nice -n 10 cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=Release >"$work/configure.log" 2>&1 || { echo "$0: configure failed, see $work/configure.log" >&2; exit 2; }
fi
nice -n 10 cmake --build "$build" -j "$jobs" >"$work/build.log" 2>&1 || { echo "$0: the unmutated copy does not build, see $work/build.log" >&2; exit 2; }
if ! run_tests; then
  echo "$0: the unmutated copy fails its tests ($(cat "$work/failed")): fix that first" >&2
  exit 2
fi

: >"$report"
total=0 killed=0 survived=0 unexpected=0 n=0
# LIST lines: file @@ original @@ mutated @@ description [@@ equivalent: reason]
grep -v -e '^#' -e '^[[:space:]]*$' "$list" >"$work/list"
while IFS= read -r line; do
  n=$((n + 1))
  if [ -n "${MUTANTS_ONLY:-}" ] && ! printf ' %s ' "$MUTANTS_ONLY" | grep -q " $n "; then continue; fi
  file=$(printf '%s\n' "$line" | awk -F' @@ ' '{print $1}')
  desc=$(printf '%s\n' "$line" | awk -F' @@ ' '{print $4}')
  equiv=$(printf '%s\n' "$line" | awk -F' @@ ' '{print $5}')
  total=$((total + 1))
  # Apply: the original text must be in exactly one line of the file.
  if ! MUT_LINE=$line perl -e '
      my ($f, $o, $m) = split / \@\@ /, $ENV{MUT_LINE};
      open(my $in, "<", $ARGV[0]) or die "cannot read $ARGV[0]\n";
      my @l = <$in>; close $in;
      my @hit = grep { index($l[$_], $o) >= 0 } 0 .. $#l;
      die "original text found in " . scalar(@hit) . " lines of $f\n" unless @hit == 1;
      substr($l[$hit[0]], index($l[$hit[0]], $o), length $o) = $m;
      open(my $out, ">", $ARGV[0]) or die; print $out @l; close $out;' "$src/$file" 2>"$work/apply.log"; then
    echo "mutant $n: $file: cannot apply: $(cat "$work/apply.log")" | tee -a "$report"
    unexpected=$((unexpected + 1))
    continue
  fi
  start=$(date +%s)
  if ! nice -n 10 cmake --build "$build" -j "$jobs" >"$work/build.log" 2>&1 </dev/null; then
    result="KILLED   (does not build)"
    killed=$((killed + 1))
  elif ! run_tests; then
    result="KILLED   (by $(cat "$work/failed"))"
    killed=$((killed + 1))
  else
    survived=$((survived + 1))
    if [ -n "$equiv" ]; then
      result="SURVIVED (equivalent: ${equiv#equivalent: })"
    else
      result="SURVIVED"
      unexpected=$((unexpected + 1))
    fi
  fi
  # Restore the file (a new mtime, so the next build recompiles it).
  cp "$here/$file" "$src/$file"
  touch "$src/$file"
  printf 'mutant %2d %s\n    %s: %s (%ss)\n' "$n" "$result" "$file" "$desc" "$(($(date +%s) - start))" | tee -a "$report"
done <"$work/list"
nice -n 10 cmake --build "$build" -j "$jobs" >"$work/build.log" 2>&1 || true

rate=$(awk -v k="$killed" -v t="$total" 'BEGIN { printf "%.0f", t ? 100 * k / t : 0 }')
{
  echo "mutants: $total run, $killed killed, $survived survived ($rate% killed)"
  if [ "$unexpected" -eq 0 ]; then echo "every mutant not marked equivalent was killed"
  else echo "$unexpected mutant(s) survived without being marked equivalent, or could not be applied"; fi
} | tee -a "$report"
[ "$unexpected" -eq 0 ]
