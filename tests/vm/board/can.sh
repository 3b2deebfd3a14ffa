#!/bin/sh
# CAN against the Linux board on vcan0: CanLink reaches it (info, config, status), and
# `tetrapulse sync --can` (CanSync) locks its clock servo. The board's local clock runs
# 40 ppm fast; rig time is CLOCK_MONOTONIC + 1000 s on the host side, so every second the
# board's own rig time for a monotonic instant gives its true error. Acceptance: within
# 200 us of rig time once locked.
set -eu
. /lib/tetrapulse/vm-lib.sh
. /lib/tetrapulse/board-lib.sh

trap 'board_stop' EXIT
board_start_can can

info=$(tetrapulse info --can vcan0:3 --json) || fail "tetrapulse info over CAN failed: $info"
echo "$info"
[ "$(json_field "$info" hw_model)" = linux ] || fail "info says hw_model $(json_field "$info" hw_model), not linux"
[ "$(json_field "$info" fw_version)" = 1.0.0 ] || fail "info says fw_version $(json_field "$info" fw_version), not 1.0.0"
[ "$(json_field "$info" node_id)" = 3 ] || fail "info says node_id $(json_field "$info" node_id), not 3"
tetrapulse config --can vcan0:3 --sync-source can || fail "tetrapulse config --sync-source can failed"
[ "$(json_field "$(tetrapulse config --can vcan0:3 --json)" sync_source)" = can ] || fail "the board's sync source is not can"

offset=1000000000000
tetrapulse sync --can vcan0 --can-rate 10 --rig-offset-ns "$offset" --duration-s 22 >/tmp/sync.txt 2>&1 &
sync_pid=$!
wait_for 15 grep -q 'clock .* sync locked' /tmp/board-can.txt || {
  tail -5 /tmp/board-can.txt
  fail "the board's servo did not lock within 15 s of CAN sync"
}
locked_at=$(board_count /tmp/board-can.txt 'clock ')
status=$(tetrapulse status --can vcan0:3 --json) || fail "tetrapulse status over CAN failed"
echo "$status"
[ "$(json_field "$status" sync_state)" = locked ] || { grep ' clock ' /tmp/board-can.txt; fail "status says sync_state $(json_field "$status" sync_state)"; }
[ "$(json_field "$status" sync_source)" = can ] || fail "status says sync_source $(json_field "$status" sync_source)"
wait "$sync_pid" || { cat /tmp/sync.txt; fail "tetrapulse sync --can failed"; }
cat /tmp/sync.txt

# The true error of the board's clock on every report after lock (+2 s of settling):
# rig_ns - (monotonic_ns + offset).
awk -v skip="$((locked_at + 2))" -v offset="$offset" '
  / clock monotonic_ns / {
    n++
    if (n <= skip) next
    for (i = 1; i <= NF; i++) { if ($i == "monotonic_ns") m = $(i + 1); if ($i == "rig_ns") r = $(i + 1); if ($i == "sync") s = $(i + 1); if ($i == "held") h = $(i + 1) }
    e = r - m - offset
    if (s != "locked") bad++
    c++; sum += e; sq += e * e; a = e < 0 ? -e : e; if (a > max) max = a
  }
  END {
    if (c < 8) { printf "only %d clock reports after lock\n", c; exit 1 }
    # busybox awk has no sqrt: Newton steps for the rms
    ms = sq / c; rms = ms > 1 ? ms : 1; for (i = 0; i < 60; i++) rms = (rms + ms / rms) / 2
    printf "can: %d reports after lock: true clock error mean %.0f ns, rms %.0f ns, max |error| %.0f ns; %d not locked; %d samples held out\n", c, sum / c, rms, max, bad, h
    if (max > 200000 || bad > 0) exit 1
  }' /tmp/board-can.txt || { grep ' clock ' /tmp/board-can.txt; fail "the board's clock left 200 us of rig time (or lost lock) under CAN sync"; }
