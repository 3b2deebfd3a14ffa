#!/bin/sh
# The gadget unbound from its UDC in the middle of `tetrapulse flash`: the CLI says that
# the board left the bus during the download, and the board stays recoverable: once the
# gadget is back, a second `tetrapulse flash` installs the image. Then unbound in the middle
# of `tetrapulse status --watch` (a command every 50 ms): one line naming the board and a
# non-zero exit; bound again, status answers.
set -eu
. /lib/tetrapulse/vm-lib.sh
. /lib/tetrapulse/board-lib.sh

tetrapulse-board image --fw-version 1.0.0 --payload-size 4096 --out /tmp/unbind-v1.img
tetrapulse-board image --fw-version 2.0.0 --payload-size 240000 --seed 7 --out /tmp/unbind-v2.img
trap 'board_stop' EXIT
# shellcheck disable=SC2046
board_start /tmp/board-unbind.txt $(board_usb_args /tmp/unbind-flash.bin) --factory-image /tmp/unbind-v1.img --dfu-idle-s 30 ||
  fail "the board did not start"
wait_for 20 lsusb -d 1209:0001 || fail "1209:0001 did not enumerate"

udc=/sys/kernel/config/usb_gadget/$BOARD_GADGET/UDC
tetrapulse flash --usb "$BOARD_SERIAL" /tmp/unbind-v2.img >/tmp/flash1.txt 2>&1 &
flash_pid=$!
wait_for 30 grep -q 'tetrapulse flash: download' /tmp/flash1.txt || { cat /tmp/flash1.txt; fail "the download never started"; }
sleep 1
bound=$(cat "$udc")
echo "" >"$udc"
echo "unbind: gadget unbound from $bound during the download"
rc=0
wait "$flash_pid" || rc=$?
cat /tmp/flash1.txt
[ "$rc" -ne 0 ] || fail "tetrapulse flash reported success although the gadget was unbound"
tail -1 /tmp/flash1.txt | grep -q 'the board left the bus during the download' ||
  fail "tetrapulse flash does not say that the board went away: $(tail -1 /tmp/flash1.txt)"

echo "$bound" >"$udc"
wait_for 20 sh -c "lsusb -d 1209:0002 || lsusb -d 1209:0001" || { cat /tmp/board-unbind.txt; fail "the board did not come back after rebinding"; }
tetrapulse flash --usb "$BOARD_SERIAL" /tmp/unbind-v2.img >/tmp/flash2.txt 2>&1 || { cat /tmp/flash2.txt /tmp/board-unbind.txt; fail "the second tetrapulse flash failed"; }
cat /tmp/flash2.txt
grep -q 'now running 2.0.0' /tmp/flash2.txt || fail "after the second flash the board does not run 2.0.0"
echo "unbind: the board recovered; the second flash installed 2.0.0"

# Mid-command: status every 50 ms while the gadget goes away.
board_wait_version 2.0.0 20 || fail "the board does not answer as 2.0.0 after the flash"
tetrapulse status --usb "$BOARD_SERIAL" --watch --interval-ms 50 >/tmp/watch.txt 2>&1 &
watch_pid=$!
wait_for 10 grep -q 'sync' /tmp/watch.txt || { cat /tmp/watch.txt; fail "status --watch printed nothing"; }
bound=$(cat "$udc")
echo "" >"$udc"
rc=0
wait "$watch_pid" || rc=$?
echo "unbind: status --watch after the unbind (exit $rc): $(tail -1 /tmp/watch.txt)"
[ "$rc" -ne 0 ] || fail "tetrapulse status --watch went on as if the board were there"
tail -1 /tmp/watch.txt | grep -q "^tetrapulse status: usb:" || fail "the last line does not name the board: $(tail -1 /tmp/watch.txt)"
echo "$bound" >"$udc"
wait_for 20 sh -c "tetrapulse status --usb $BOARD_SERIAL >/dev/null 2>&1" || fail "status does not answer after rebinding"
echo "unbind: status answers again after rebinding"
