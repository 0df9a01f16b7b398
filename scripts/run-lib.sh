# Sourced by the scripts that drive a built ldmbench over a sweep (default-sweep.sh,
# readme-main.sh): the binary, and the exit status they share.
#   source "$(dirname "$0")/run-lib.sh"; require_ldmbench NAME.sh

# $ldmbench: $LDMBENCH, else build/ldmbench; exits 2 naming the calling script where it is not built.
require_ldmbench() {
  ldmbench="${LDMBENCH:-build/ldmbench}"
  [[ -x "$ldmbench" ]] || { echo "$1: $ldmbench not built (cmake --build build)" >&2; exit 2; }
}

# Runs "$@". Its exit status 3 (some configuration failed, recorded as failed; the sweep went
# on) is kept in $status for the script's own exit and the script goes on; any other failure
# ends the script with that status.
status=0
keep_failed() {
  "$@" || { local s=$?; [[ $s -eq 3 ]] || exit $s; status=3; }
}
