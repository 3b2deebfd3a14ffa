#!/bin/sh
# vcan: an extended-id frame sent with cansend reaches candump carrying a
# kernel receive timestamp near the wall clock; can_timestamp_probe then
# reports which transmit timestamps vcan gives (the facts CAN sync builds on).
set -eu
. /lib/tetrapulse/vm-lib.sh

ip link add dev vcan0 type vcan || fail "cannot create vcan0"
ip link set up vcan0

candump -t a -n 1 vcan0 >/tmp/candump.txt 2>&1 &
dump=$!
# candump must be listening before the frame goes out (it starts slowly under
# TCG): its raw socket shows in the kernel's receive list for vcan0 once bound.
# An empty list still names the device, as "(vcan0: no entry)".
wait_for 10 sh -c "grep -v 'no entry' /proc/net/can/rcvlist_all | grep -q vcan0" ||
  fail "candump did not start listening on vcan0 within 10 s"
sent=$(date +%s)
cansend vcan0 1ABCDE01#DEADBEEF
wait_for 10 sh -c "! kill -0 $dump" || fail "candump saw no frame within 10 s"
cat /tmp/candump.txt
# " (1700000000.123456)  vcan0  1ABCDE01   [4]  DE AD BE EF"
# shellcheck disable=SC2046 # split into fields on purpose
set -- $(tr -d '()' </tmp/candump.txt)
[ "$#" -eq 8 ] || fail "candump printed '$*', not one frame"
[ "$2" = vcan0 ] && [ "$3" = 1ABCDE01 ] && [ "$4" = "[4]" ] || fail "frame header '$2 $3 $4' is not vcan0 1ABCDE01 [4]"
[ "$5 $6 $7 $8" = "DE AD BE EF" ] || fail "frame data '$5 $6 $7 $8' is not DE AD BE EF"
stamp=${1%.*}
[ "$stamp" -gt 0 ] || fail "candump shows no kernel receive timestamp ($1)"
[ $((stamp - sent)) -ge -1 ] && [ $((stamp - sent)) -le 5 ] ||
  fail "receive timestamp $1 is not within 5 s of the send time $sent (CLOCK_REALTIME expected)"
echo "vcan: extended frame received, kernel rx timestamp $1 (sent at ~$sent)"

can_timestamp_probe vcan0 >/tmp/probe.txt 2>&1 || { cat /tmp/probe.txt; fail "can_timestamp_probe failed"; }
cat /tmp/probe.txt
grep -q 'own frame looped back: yes, rx software timestamp: yes' /tmp/probe.txt ||
  fail "the own frame came back without a receive timestamp"
