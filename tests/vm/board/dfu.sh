#!/bin/sh
# USB DFU into the Linux board. Debian's dfu-util detaches the application (DFU run-time
# interface), downloads into the DFU-mode bootloader and resets; the board then runs and
# reports the new version. `tetrapulse flash` does the same. A corrupted image is refused
# (errVERIFY) and the board returns to the image it had.
set -eu
. /lib/tetrapulse/vm-lib.sh
. /lib/tetrapulse/board-lib.sh

seed=1
for v in 1.0.0 1.1.0 1.2.0 1.3.0; do
  tetrapulse-board image --fw-version "$v" --payload-size 65536 --seed "$seed" --out "/tmp/dfu-$v.img"
  seed=$((seed + 1))
done
# The 1.3.0 image with one payload byte changed: its header (and header CRC) stays valid.
cp /tmp/dfu-1.3.0.img /tmp/dfu-bad.img
printf '\125' | dd of=/tmp/dfu-bad.img bs=1 seek=30000 conv=notrunc 2>/dev/null
cmp -s /tmp/dfu-1.3.0.img /tmp/dfu-bad.img && fail "the corrupted image is not corrupted"

trap 'board_stop' EXIT
# shellcheck disable=SC2046
board_start /tmp/board-dfu.txt $(board_usb_args /tmp/dfu-flash.bin) --factory-image /tmp/dfu-1.0.0.img --dfu-idle-s 8 ||
  fail "the board did not start"
wait_for 20 lsusb -d 1209:0001 || fail "1209:0001 did not enumerate"

# dfu-util in two runs: -e detaches the application, -D downloads into the DFU-mode
# bootloader. One `dfu-util -D` does both where udevd runs; this VM has none, so libusb
# (built for udev) gets no hotplug events inside a running process and dfu-util's re-probe
# after the detach cannot see the re-enumerated device. A new process scans sysfs afresh.
dfu_util_flash() {
  dfu-util -d 1209:0001 -e >/tmp/dfu-detach.txt 2>&1 || { cat /tmp/dfu-detach.txt; return 1; }
  wait_for 30 lsusb -d 1209:0002 || { echo "no DFU-mode device 1209:0002 after the detach"; return 1; }
  dfu-util -d 1209:0002 -D "$1" -R
}

version() {
  json_field "$(tetrapulse info --usb "$BOARD_SERIAL" --json 2>/dev/null)" fw_version
}
# After a download the new image runs on trial; it confirms itself after 5 s and a request.
wait_confirmed() {
  wait_for 20 sh -c "tetrapulse status --usb $BOARD_SERIAL >/dev/null 2>&1; grep -q 'image $1 in slot . confirmed' /tmp/board-dfu.txt" ||
    fail "image $1 did not confirm itself"
}

started=$(cut -d' ' -f1 /proc/uptime)
dfu_util_flash /tmp/dfu-1.1.0.img >/tmp/dfu-util.txt 2>&1 || { cat /tmp/dfu-util.txt; cat /tmp/board-dfu.txt; fail "dfu-util -D failed"; }
cat /tmp/dfu-util.txt
wait_for 20 lsusb -d 1209:0001 || { cat /tmp/board-dfu.txt; fail "the board did not come back as 1209:0001 after dfu-util"; }
board_wait_version 1.1.0 15 ||
  { cat /tmp/board-dfu.txt; fail "after dfu-util the board runs $(version), not 1.1.0"; }
echo "dfu: dfu-util -D installed 1.1.0 in $(($(cut -d. -f1 /proc/uptime) - ${started%.*})) s"
wait_confirmed 1.1.0

tetrapulse flash --usb "$BOARD_SERIAL" /tmp/dfu-1.2.0.img >/tmp/flash.txt 2>&1 || { cat /tmp/flash.txt /tmp/board-dfu.txt; fail "tetrapulse flash failed"; }
cat /tmp/flash.txt
grep -q 'now running 1.2.0' /tmp/flash.txt || fail "tetrapulse flash does not say the board runs 1.2.0"
[ "$(version)" = 1.2.0 ] || fail "after tetrapulse flash the board runs $(version), not 1.2.0"
wait_confirmed 1.2.0

# The corrupted image: the host CLI checks the payload CRC before sending anything...
if tetrapulse flash --usb "$BOARD_SERIAL" /tmp/dfu-bad.img >/tmp/flash-bad.txt 2>&1; then fail "tetrapulse flash took a corrupted image"; fi
cat /tmp/flash-bad.txt
# ...and the board refuses it from dfu-util, which does not (dfu-util 0.11 prints the
# device's dfuERROR / errVERIFY status after manifestation and still exits 0).
dfu_util_flash /tmp/dfu-bad.img >/tmp/dfu-bad.txt 2>&1 || :
grep -v '^Download' /tmp/dfu-bad.txt | tail -5
grep -q 'status(7)' /tmp/dfu-bad.txt || fail "dfu-util did not see errVERIFY (status 7) from the board"
grep -q 'download refused: errVERIFY' /tmp/board-dfu.txt || { cat /tmp/board-dfu.txt; fail "the board did not refuse the corrupted image with errVERIFY"; }
# Back to its application after the DFU idle time (8 s): still 1.2.0.
wait_for 40 sh -c "grep -q 'back to the application' /tmp/board-dfu.txt && lsusb -d 1209:0001" || fail "the board did not return to its application"
board_wait_version 1.2.0 15 ||
  { cat /tmp/board-dfu.txt; fail "after the refused image the board runs $(version), not 1.2.0"; }
echo "dfu: corrupted image refused (errVERIFY), the board kept 1.2.0"
