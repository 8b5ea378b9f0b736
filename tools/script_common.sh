# script_common.sh - shared set-up of the project's shell scripts (sourced, POSIX sh):
#   require_built EXE...   stop unless every EXE exists (the build was made)
#   require_gnuplot        stop unless gnuplot is installed
#   set_mpiexec            MPIEXEC for one rank, unless set; Open MPI as root needs two flags
#   make_workdir NAME      tmp = a new temporary directory, removed when the script exits

require_built() {
  for exe in "$@"; do
    if [ ! -x "$exe" ]; then
      echo "$0: $exe not found: build the project first (cmake --build <build dir>)" >&2
      exit 1
    fi
  done
}

require_gnuplot() {
  if ! command -v gnuplot >/dev/null 2>&1; then
    echo "$0: gnuplot not found (Debian: apt-get install gnuplot-nox)" >&2
    exit 1
  fi
}

set_mpiexec() {
  if [ -z "${MPIEXEC:-}" ]; then
    MPIEXEC="mpiexec -n 1"
    if [ "$(id -u)" = 0 ] && mpiexec --version 2>/dev/null | grep -q -e "Open MPI" -e "OpenRTE"; then
      MPIEXEC="$MPIEXEC --allow-run-as-root --oversubscribe"
    fi
  fi
}

make_workdir() {
  tmp=$(mktemp -d "${TMPDIR:-/tmp}/$1.XXXXXX")
  trap 'rm -rf "$tmp"' EXIT
  trap 'exit 130' INT TERM
}
