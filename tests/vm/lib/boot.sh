# Boots the VM, streams its console and turns verdict lines into an exit status (sourced).
# shellcheck shell=bash

# vm_boot VMLINUZ INITRD VM_LIMIT TEST_LIMIT LOG NAME...: runs qemu with the
# console on stdout and in LOG, then judges the run (vm_judge).
vm_boot() {
  local vmlinuz=$1 initrd=$2 vm_limit=$3 test_limit=$4 log=$5
  shift 5
  local qemu nonce rc
  qemu=$(command -v qemu-system-x86_64) || vm_unavailable "qemu-system-x86_64 is not installed (Debian package qemu-system-x86)"
  nonce=$(od -An -N8 -tx8 /dev/urandom | tr -d ' \n')
  local append="console=ttyS0 quiet panic=-1 tp.nonce=$nonce tp.test_timeout=$test_limit ${TETRAPULSE_VM_APPEND:-}"
  # No KVM: the machines' CPUs lack vmx/svm, so TCG it is.
  set +e
  timeout -k 5 "$vm_limit" "$qemu" -accel tcg -m 1024 -smp 1 -nographic -no-reboot -net none \
    -kernel "$vmlinuz" -initrd "$initrd" -append "$append" </dev/null 2>&1 |
    sed -u 's/\r$//' | tee "$log"
  rc=${PIPESTATUS[0]}
  set -e
  vm_judge "$log" "$nonce" "$rc" "$vm_limit" "$test_limit" "$@"
}

# vm_test_log LOG NONCE NAME: the console lines test NAME printed.
vm_test_log() {
  awk -v start="=== test $3" -v stop="TETRAPULSE-VM $2 " '
    $0 == start { on = 1; next }
    on && index($0, stop) == 1 { exit }
    on { print }' "$1"
}

# vm_judge LOG NONCE QEMU_STATUS VM_LIMIT TEST_LIMIT NAME...: prints PASS or
# FAIL with the reason for each test. Returns 0 when all passed; with one test
# that failed, its status (never the skip code). With VM_VERDICT_DIR set it
# also writes NAME.status (exit status, or a reason) and NAME.log per test and
# returns 0 when every test got a verdict, pass or fail; tests/vm/verdict reads them.
vm_judge() {
  local log=$1 nonce=$2 qemu_rc=$3 vm_limit=$4 test_limit=$5
  shift 5
  local marker="TETRAPULSE-VM $nonce" line name status reason failed=0 missing=0 last_rc=0 panic
  panic=$(grep -m1 -E 'Kernel panic|BUG: |Oops: ' "$log" || true)
  local boot_failure
  boot_failure=$(grep -m1 "^$marker BOOT-FAILED" "$log" || true)
  for name in "$@"; do
    line=$(grep -m1 -E "^$marker (VERDICT|TIMEOUT) $name [0-9]+$" "$log" || true)
    status=${line##* }
    reason=
    if [ -n "$boot_failure" ]; then
      reason="the VM could not set up: ${boot_failure#"$marker BOOT-FAILED "}"
    elif [ -z "$line" ] && [ -n "$panic" ]; then
      reason="the kernel crashed before the test finished: $panic"
    elif [ -z "$line" ] && { [ "$qemu_rc" -eq 124 ] || [ "$qemu_rc" -eq 137 ]; }; then
      reason="the VM did not finish within $vm_limit s (raise --timeout or TETRAPULSE_VM_TIMEOUT)"
    elif [ -z "$line" ]; then
      reason="no verdict: the VM stopped before the test finished (qemu exited with status $qemu_rc)"
    elif [[ $line == "$marker TIMEOUT "* ]]; then
      reason="timed out inside the VM (limit $test_limit s per test)"
    elif [ "$status" -ne 0 ]; then
      reason="exit status $status"
    fi
    [ -n "$line" ] || missing=1
    if [ -z "$reason" ]; then
      echo "run-vm: PASS $name"
    else
      echo "run-vm: FAIL $name: $reason" >&2
      failed=1
      last_rc=1
      [[ $reason == "exit status "* ]] && last_rc=$status
    fi
    if [ -n "${VM_VERDICT_DIR:-}" ]; then
      vm_test_log "$log" "$nonce" "$name" >"$VM_VERDICT_DIR/$name.log"
      if [ -z "$reason" ]; then echo 0; elif [[ $reason == "exit status "* ]]; then echo "$status"; else echo "$reason"; fi \
        >"$VM_VERDICT_DIR/$name.status"
    fi
  done
  if [ -n "$panic" ]; then
    [ "$missing" -eq 1 ] || echo "run-vm: FAIL: the kernel reported a fault during the run: $panic" >&2
    return 1
  fi
  if [ -n "${VM_VERDICT_DIR:-}" ]; then
    [ "$missing" -eq 0 ] && [ -z "$boot_failure" ]
    return
  fi
  [ "$failed" -eq 0 ] && return 0
  # One test: its own status, except one CTest would read as "skipped".
  if [ "$#" -eq 1 ] && [ "$last_rc" -ne "$VM_SKIP_CODE" ] && [ "$last_rc" -lt 126 ]; then
    return "$last_rc"
  fi
  return 1
}
