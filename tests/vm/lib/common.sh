# Shared by the tests/vm scripts (sourced): messages, the skip rule, the cache lock.
# shellcheck shell=bash

# CTest shows a test that exits with this code as skipped (SKIP_RETURN_CODE).
readonly VM_SKIP_CODE=77

vm_log() { printf 'tests/vm: %s\n' "$*" >&2; }

# A fault in the harness or in what it builds: always a failure.
vm_die() {
  printf 'tests/vm: ERROR: %s\n' "$*" >&2
  exit 1
}

# The machine lacks what a VM needs (qemu, the Debian archive). That is a loud
# failure, unless TETRAPULSE_SKIP_VM=1 says it is expected here: then a loud skip.
vm_unavailable() {
  if [ "${TETRAPULSE_SKIP_VM:-0}" = 1 ]; then
    [ -z "${VM_VERDICT_DIR:-}" ] || printf '%s\n' "$*" >"$VM_VERDICT_DIR/skipped"
    printf '\n*** SKIPPED (TETRAPULSE_SKIP_VM=1): VM test not run: %s ***\n\n' "$*" >&2
    exit "$VM_SKIP_CODE"
  fi
  printf 'tests/vm: ERROR: the test VM cannot run: %s\n' "$*" >&2
  printf 'tests/vm: set TETRAPULSE_SKIP_VM=1 to report VM tests as skipped on such machines.\n' >&2
  exit 1
}

# vm_with_lock FILE CMD...: runs CMD holding an exclusive lock on FILE, so that
# parallel test runs share one cache without building it twice.
vm_with_lock() {
  local lockfile=$1
  shift
  (
    exec 9>"$lockfile"
    if ! flock -n 9; then
      vm_log "waiting for another run to finish preparing the cache ($lockfile)"
      flock 9
    fi
    "$@"
  )
}

# vm_timed WHAT CMD...: runs CMD and logs how long WHAT took.
vm_timed() {
  local what=$1 t0=$SECONDS
  shift
  "$@"
  vm_log "$what: $((SECONDS - t0)) s"
}
