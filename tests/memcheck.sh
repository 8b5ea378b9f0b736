#!/bin/sh
# memcheck.sh COMMAND [ARGS...]: runs COMMAND under valgrind memcheck and fails if any error
# (invalid access, use of uninitialised values, bad free) or any definite/indirect leak has
# petsc-vshmm's own code in its stack. MPI's and PETSc's own one-time allocations are not ours
# and are ignored. Prints the offending records.
set -u
command -v valgrind >/dev/null 2>&1 || { echo "memcheck.sh: valgrind not found"; exit 1; }
log=$(mktemp)
trap 'rm -f "$log"' EXIT
valgrind --leak-check=full --show-leak-kinds=definite,indirect --num-callers=50 \
  --log-file="$log" "$@" >/dev/null
status=$?
if [ "$status" -ne 0 ]; then echo "memcheck.sh: the program failed (exit $status)"; exit 1; fi
# One record per paragraph once valgrind's ==pid== prefixes are gone.
sed 's/^==[0-9]*== \{0,1\}//' "$log" | awk '
  BEGIN { RS = ""; bad = 0 }
  /(Invalid|uninitialised|Mismatched|definitely lost|indirectly lost|overlap|free\(\))/ &&
  /(libpetscvshmm|VSHMM|vshmm::)/ { print; print "----"; bad++ }
  /ERROR SUMMARY/ { summary = $0 }
  END { print summary; if (bad) { print bad " record(s) involve petsc-vshmm"; exit 1 } print "memcheck.sh: no errors or leaks in petsc-vshmm" }'
