#!/bin/sh
# CAN faults against the Linux board on vcan0 while `tetrapulse sync --can` keeps it locked:
#  - a loaded bus: cangen sends 8-byte extended frames of another node in bursts of 24
#    every 2 ms (12000 frames/s asked; the rate reached is measured and reported against a
#    1 Mbit/s bus, about 135 bits a frame: 7400 frames/s is 100 %, 5900 is 80 %); the
#    board's kernel filters drop them, and it must stay locked;
#  - error frames as a controller reports them (linux/can/error.h), injected on the bus:
#    error-passive, bus-off, restarted. The board counts them, `tetrapulse status` shows
#    BUS-OFF while it lasts and the count after; sync stays locked (Sync frames keep
#    coming on vcan, which has no controller to go bus-off).
set -eu
. /lib/tetrapulse/vm-lib.sh
. /lib/tetrapulse/board-lib.sh

trap 'board_stop; kill "${gen_pid:-}" 2>/dev/null || :' EXIT
board_start_can cf
tetrapulse config --can vcan0:3 --sync-source can >/dev/null || fail "tetrapulse config --sync-source can failed"

tetrapulse sync --can vcan0 --can-rate 10 --rig-offset-ns 1000000000000 --duration-s 40 >/tmp/cf-sync.txt 2>&1 &
sync_pid=$!
wait_for 15 grep -q 'clock .* sync locked' /tmp/board-cf.txt || { tail -5 /tmp/board-cf.txt; fail "no lock within 15 s"; }
reports_locked=$(board_count /tmp/board-cf.txt 'clock ')

# The load: bursts of 24 frames every 2 ms (the emulated machine oversleeps), node 9's ids.
uptime_s() { cut -d' ' -f1 /proc/uptime; }
tx_before=$(cat /sys/class/net/vcan0/statistics/tx_packets)
load_from=$(uptime_s)
cangen vcan0 -g 2 -c 24 -e -I 12345609 -L 8 -D i -n 72000 &
gen_pid=$!
wait "$gen_pid" || fail "cangen failed"
gen_pid=
load_to=$(uptime_s)
tx=$(($(cat /sys/class/net/vcan0/statistics/tx_packets) - tx_before))
rate=$(awk -v n="$tx" -v a="$load_from" -v b="$load_to" 'BEGIN { printf "%d", n / (b - a) }')
echo "canfaults: $tx frames in $load_from..$load_to s: $rate frames/s ($((rate * 100 / 7400)) % of a 1 Mbit/s bus)"
[ "$rate" -ge 5900 ] || echo "canfaults: note: below 80 % of a 1 Mbit/s bus (the emulated machine's limit)"
status=$(tetrapulse status --can vcan0:3 --json) || fail "status under load failed"
[ "$(json_field "$status" sync_state)" = locked ] || fail "under load the board is $(json_field "$status" sync_state)"
# Every clock report after the lock's, through the load, says locked.
unlocked=$(awk -v skip="$reports_locked" '/ clock / { n++; if (n > skip && $0 !~ /sync locked/) bad++ } END { print bad + 0 }' /tmp/board-cf.txt)
[ "$unlocked" -eq 0 ] || { grep ' clock ' /tmp/board-cf.txt; fail "$unlocked clock reports out of lock under load"; }
echo "canfaults: locked all through the load ($(board_count /tmp/board-cf.txt 'clock ') clock reports)"

# Error-passive: CAN_ERR_CRTL (0x4) with data[1] = RX and TX passive (0x10 | 0x20).
cansend vcan0 20000004#0030000000000000
# Bus-off (0x40): the board says so in its status, the host's link refuses.
cansend vcan0 20000040#0000000000000000
wait_for 5 sh -c 'tetrapulse status --can vcan0:3 --json 2>/dev/null | grep -q "\"can_bus_off\": true"' || {
  tetrapulse status --can vcan0:3 || :
  fail "the board's status does not show bus-off"
}
wait_for 5 sh -c 'tetrapulse status --can vcan0:3 >/tmp/cf-status.txt 2>&1 && grep -q BUS-OFF /tmp/cf-status.txt' || {
  cat /tmp/cf-status.txt
  fail "status text does not say BUS-OFF"
}
echo "canfaults: status during bus-off: $(cat /tmp/cf-status.txt)"
# Restarted (0x100): the board is back on the bus; its error count stays.
cansend vcan0 20000100#0000000000000000
wait_for 5 sh -c 'tetrapulse status --can vcan0:3 --json 2>/dev/null | grep -q "\"can_bus_off\": false"' ||
  fail "the board's status still shows bus-off after the restart"
status=$(tetrapulse status --can vcan0:3 --json)
echo "$status"
errors=$(json_field "$status" can_errors)
[ "$errors" -ge 3 ] || fail "the board counted $errors CAN errors, not at least 3"
[ "$(json_field "$status" sync_state)" = locked ] || fail "after the error frames the board is $(json_field "$status" sync_state)"
wait "$sync_pid" || { cat /tmp/cf-sync.txt; fail "tetrapulse sync --can failed"; }
echo "canfaults: error-passive, bus-off and restart shown; $errors CAN errors counted; still locked"
