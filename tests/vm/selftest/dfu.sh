#!/bin/sh
# DFU run-time interface through FunctionFS: the kernel accepts the DFU
# functional descriptor (type 0x21), lsusb decodes it and dfu-util -l lists
# the run-time interface.
set -eu
. /lib/tetrapulse/vm-lib.sh

cleanup() {
  set +e
  [ -z "${gadget_pid:-}" ] || kill "$gadget_pid" 2>/dev/null || true
  [ -z "${gadget_pid:-}" ] || wait "$gadget_pid" 2>/dev/null || true
  usb_gadget_remove dfu
}
trap cleanup EXIT

usb_gadget_ffs dfu 0x1209 0x0001 || fail "cannot create the configfs gadget with a FunctionFS function"
ffs_selftest --dfu-runtime /dev/ffs/dfu >/tmp/gadget.txt 2>&1 &
gadget_pid=$!
wait_for 10 sh -c "grep -q 'descriptors accepted' /tmp/gadget.txt || ! kill -0 $gadget_pid" || true
if ! grep -q 'descriptors accepted' /tmp/gadget.txt; then
  cat /tmp/gadget.txt
  fail "kernel $(uname -r) refuses a DFU functional descriptor through FunctionFS"
fi
usb_gadget_bind dfu || fail "cannot bind the gadget to $(ls /sys/class/udc)"
wait_for 20 lsusb -d 1209:0001 || { cat /tmp/gadget.txt; fail "lsusb does not see 1209:0001 within 20 s"; }
lsusb -v -d 1209:0001 2>/dev/null >/tmp/lsusb.txt || true
grep -A8 'Device Firmware Upgrade' /tmp/lsusb.txt || fail "lsusb -v shows no DFU functional descriptor"
grep -q 'bcdDFUVersion *1.10' /tmp/lsusb.txt || fail "the DFU functional descriptor does not say DFU 1.1"
dfu-util -l >/tmp/dfu.txt 2>&1 || true
cat /tmp/dfu.txt
grep -q 'Found Runtime: \[1209:0001\]' /tmp/dfu.txt || fail "dfu-util -l does not list the run-time interface of 1209:0001"
grep -qi 'warning' /tmp/dfu.txt && fail "dfu-util warned while listing (functional descriptor not seen?)"
echo "dfu: kernel $(uname -r) passes the DFU functional descriptor; dfu-util lists the run-time interface"
