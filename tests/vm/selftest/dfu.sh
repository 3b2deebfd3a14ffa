#!/bin/sh
# DFU run-time interface through FunctionFS: the kernel accepts the DFU
# functional descriptor (type 0x21), lsusb decodes it and dfu-util -l lists
# the run-time interface.
set -eu
. /lib/tetrapulse/vm-lib.sh

trap 'usb_gadget_stop dfu' EXIT
if ! usb_gadget_start dfu 0x1209 0x0001 /tmp/gadget.txt 'descriptors accepted' ffs_selftest --dfu-runtime /dev/ffs/dfu; then
  cat /tmp/gadget.txt
  grep -q 'refused the descriptors' /tmp/gadget.txt &&
    fail "kernel $(uname -r) refuses a DFU functional descriptor through FunctionFS"
  fail "the DFU gadget did not come up as 1209:0001"
fi
lsusb -v -d 1209:0001 2>/dev/null >/tmp/lsusb.txt || true
grep -A9 'Device Firmware Upgrade' /tmp/lsusb.txt || fail "lsusb -v shows no DFU functional descriptor"
grep -q 'bcdDFUVersion *1.10' /tmp/lsusb.txt || fail "the DFU functional descriptor does not say DFU 1.1"
dfu-util -l >/tmp/dfu.txt 2>&1 || true
cat /tmp/dfu.txt
grep -q 'Found Runtime: \[1209:0001\]' /tmp/dfu.txt || fail "dfu-util -l does not list the run-time interface of 1209:0001"
if grep -qi 'warning' /tmp/dfu.txt; then
  fail "dfu-util warned while listing (functional descriptor not seen?)"
fi
echo "dfu: kernel $(uname -r) passes the DFU functional descriptor; dfu-util lists the run-time interface"
