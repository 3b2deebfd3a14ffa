#!/bin/sh
# dummy_hcd + FunctionFS: the ffs_selftest gadget binds to dummy_udc.0, lsusb
# sees 1209:0001, and usb_echo_probe (libusb) round-trips bulk data through it.
set -eu
. /lib/tetrapulse/vm-lib.sh

cleanup() {
  set +e
  [ -z "${gadget_pid:-}" ] || kill "$gadget_pid" 2>/dev/null || true
  [ -z "${gadget_pid:-}" ] || wait "$gadget_pid" 2>/dev/null || true
  usb_gadget_remove selftest
}
trap cleanup EXIT

usb_gadget_ffs selftest 0x1209 0x0001 || fail "cannot create the configfs gadget with a FunctionFS function"
ffs_selftest /dev/ffs/selftest >/tmp/gadget.txt 2>&1 &
gadget_pid=$!
wait_for 10 grep -q 'descriptors accepted' /tmp/gadget.txt || { cat /tmp/gadget.txt; fail "ffs_selftest did not get its descriptors accepted"; }
usb_gadget_bind selftest || fail "cannot bind the gadget to $(ls /sys/class/udc)"
wait_for 20 lsusb -d 1209:0001 || { cat /tmp/gadget.txt; fail "lsusb does not see 1209:0001 within 20 s"; }
lsusb -d 1209:0001
lsusb -v -d 1209:0001 2>/dev/null | grep -E 'bEndpointAddress|bInterfaceClass|iInterface' || true
usb_echo_probe 1209:0001 || { cat /tmp/gadget.txt; fail "bulk echo through the gadget failed"; }
grep -q 'event ENABLE' /tmp/gadget.txt || fail "the gadget never saw FUNCTIONFS_ENABLE"
