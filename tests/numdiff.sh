#!/bin/sh
# numdiff.sh - compare two text files, numbers within a tolerance.
#
# Usage: numdiff.sh [-r RTOL] [-a ATOL] [-q] EXPECTED ACTUAL
#
# Both files are split into tokens: runs of white space separate tokens, and every number
# (e.g. 12, -3.5, .5e-3, 1.E+04) inside a word is a token of its own, so "t=0.25," gives
# "t=", "0.25" and ",". Text tokens must be equal; two numbers a, b are equal when
#     |a - b| <= ATOL   or   |a - b| <= RTOL * max(|a|, |b|)
# (defaults RTOL = 1e-6, ATOL = 1e-10). Line breaks and the amount of white space do not
# matter. On the first difference it prints where it is and exits with 1; it exits with 0
# when the files match and with 2 on a usage error or an unreadable file. -q: print nothing.

usage() {
  echo "usage: $0 [-r RTOL] [-a ATOL] [-q] EXPECTED ACTUAL" >&2
  exit 2
}

rtol=1e-6
atol=1e-10
quiet=0
while getopts r:a:qh opt; do
  case $opt in
    r) rtol=$OPTARG ;;
    a) atol=$OPTARG ;;
    q) quiet=1 ;;
    *) usage ;;
  esac
done
shift $((OPTIND - 1))
[ $# -eq 2 ] || usage
for f in "$1" "$2"; do
  if [ ! -r "$f" ] || [ -d "$f" ]; then
    echo "$0: cannot read '$f'" >&2
    exit 2
  fi
done
for t in "$rtol" "$atol"; do
  case $t in
    '' | *[!0-9eE.+-]*) echo "$0: bad tolerance '$t'" >&2; exit 2 ;;
  esac
done

LC_ALL=C awk -v rtol="$rtol" -v atol="$atol" -v quiet="$quiet" -v f1="$1" -v f2="$2" '
# Reads file number k (name f) into tok[k, i], num[k, i] (1 for a number), lin[k, i].
function readfile(k, f,    l, nl, i, w, s, before) {
  nl = 0
  while ((getline l < f) > 0) {
    nl++
    sub(/\r$/, "", l)
    $0 = l
    for (i = 1; i <= NF; i++) {
      w = $i
      while (w != "") {
        if (!match(w, NUMRE)) { add(k, w, 0, nl); break }
        s = substr(w, RSTART, RLENGTH)
        before = substr(w, 1, RSTART - 1)
        # a sign right after a letter or digit ("x-1", "rk-4") is text, not part of the number
        if (s ~ /^[-+]/ && before ~ /[A-Za-z0-9_.]$/) {
          before = before substr(s, 1, 1); s = substr(s, 2)
        }
        if (before != "") add(k, before, 0, nl)
        add(k, s, 1, nl)
        w = substr(w, RSTART + RLENGTH)
      }
    }
  }
  close(f)
}
function add(k, s, isnum, nl) {
  n[k]++
  tok[k, n[k]] = s
  num[k, n[k]] = isnum
  lin[k, n[k]] = nl
}
function abs(x) { return x < 0 ? -x : x }
function differ(msg) {
  if (!quiet) print "numdiff: " msg
  exit 1
}
BEGIN {
  NUMRE = "[-+]?([0-9]+[.]?[0-9]*|[.][0-9]+)([eE][-+]?[0-9]+)?"
  rtol += 0; atol += 0
  n[1] = n[2] = 0
  readfile(1, f1)
  readfile(2, f2)
  m = n[1] < n[2] ? n[1] : n[2]
  for (i = 1; i <= m; i++) {
    a = tok[1, i]; b = tok[2, i]
    where = f1 ":" lin[1, i] " vs " f2 ":" lin[2, i] ": "
    if (num[1, i] && num[2, i]) {
      x = a + 0; y = b + 0
      d = abs(x - y)
      scale = abs(x) > abs(y) ? abs(x) : abs(y)
      if (d > atol && d > rtol * scale)
        differ(where "numbers differ: " a " vs " b " (abs diff " sprintf("%.3g", d) \
               ", rel diff " sprintf("%.3g", d / scale) "; tolerances rel " rtol ", abs " atol ")")
    } else if (a != b || num[1, i] != num[2, i]) {
      differ(where "\"" a "\" vs \"" b "\"")
    }
  }
  if (n[1] > n[2])
    differ(f2 " ends early; " f1 ":" lin[1, m + 1] " continues with \"" tok[1, m + 1] "\"")
  if (n[2] > n[1])
    differ(f1 " ends early; " f2 ":" lin[2, m + 1] " continues with \"" tok[2, m + 1] "\"")
  exit 0
}'
