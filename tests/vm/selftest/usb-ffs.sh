#!/bin/sh
# dummy_hcd + FunctionFS: the ffs_selftest gadget binds to dummy_udc.0, lsusb
# sees 1209:0001, and usb_echo_probe (libusb) round-trips bulk data through it.
set -eu
. /lib/tetrapulse/vm-lib.sh

trap 'usb_gadget_stop selftest' EXIT
if ! usb_gadget_start selftest 0x1209 0x0001 /tmp/gadget.txt 'descriptors accepted' ffs_selftest /dev/ffs/selftest; then
  cat /tmp/gadget.txt
  fail "the self-test gadget did not come up as 1209:0001 on $(ls /sys/class/udc)"
fi
lsusb -d 1209:0001
lsusb -v -d 1209:0001 2>/dev/null | grep -E 'bEndpointAddress|bInterfaceClass|iInterface' || true
usb_echo_probe 1209:0001 || { cat /tmp/gadget.txt; fail "bulk echo through the gadget failed"; }
grep -q 'event ENABLE' /tmp/gadget.txt || fail "the gadget never saw FUNCTIONFS_ENABLE"
