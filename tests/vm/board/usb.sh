#!/bin/sh
# dummy_hcd + FunctionFS: the Linux board's gadget as USB sees it. `tetrapulse list`
# discovers it (product string and PROTOCOL_INFO through UsbLink), `info`, `config`
# (persisted, then read back after a reboot) and `status` go over its bulk endpoints.
set -eu
. /lib/tetrapulse/vm-lib.sh
. /lib/tetrapulse/board-lib.sh

tetrapulse-board image --fw-version 1.0.0 --payload-size 4096 --out /tmp/usb-v1.img
trap 'board_stop' EXIT
# shellcheck disable=SC2046 # the arguments are words on purpose
board_start /tmp/board-usb.txt $(board_usb_args /tmp/usb-flash.bin) --factory-image /tmp/usb-v1.img ||
  fail "the board did not start with a USB gadget"
wait_for 20 lsusb -d 1209:0001 || { cat /tmp/board-usb.txt; fail "1209:0001 did not enumerate"; }
lsusb -v -d 1209:0001 2>/dev/null | grep -E 'iProduct|iSerial|bInterfaceClass|bEndpointAddress|bcdDFUVersion' || :

list=$(tetrapulse list --json 2>&1) || fail "tetrapulse list failed: $list"
echo "$list"
echo "$list" | grep -q "$BOARD_SERIAL" || fail "tetrapulse list does not show the board $BOARD_SERIAL"

info=$(tetrapulse info --usb "$BOARD_SERIAL" --json) || fail "tetrapulse info over USB failed: $info"
echo "$info"
[ "$(json_field "$info" hw_model)" = linux ] || fail "info says hw_model $(json_field "$info" hw_model)"
[ "$(json_field "$info" fw_version)" = 1.0.0 ] || fail "info says fw_version $(json_field "$info" fw_version)"
[ "$(json_field "$info" serial)" = "$BOARD_SERIAL" ] || fail "info says serial $(json_field "$info" serial)"

tetrapulse config --usb "$BOARD_SERIAL" --target-id 42 --node-id 9 --persist || fail "tetrapulse config --persist over USB failed"
tetrapulse identify --usb "$BOARD_SERIAL" --pattern blink --duration-ms 500 || fail "tetrapulse identify over USB failed"
status=$(tetrapulse status --usb "$BOARD_SERIAL" --json) || fail "tetrapulse status over USB failed"
echo "$status"
[ "$(json_field "$status" sync_state)" = free_running ] || [ "$(json_field "$status" sync_state)" = free-running ] ||
  fail "status says sync_state $(json_field "$status" sync_state) with no sync source"

# The stored configuration outlives a reset (the daemon re-executes and boots from its flash file).
board_stop
# shellcheck disable=SC2046
board_start /tmp/board-usb2.txt $(board_usb_args /tmp/usb-flash.bin) || fail "the board did not start again"
wait_for 20 lsusb -d 1209:0001 || fail "1209:0001 did not enumerate after the restart"
config=$(tetrapulse config --usb "$BOARD_SERIAL" --json) || fail "reading the configuration back failed"
echo "$config"
[ "$(json_field "$config" target_id)" = 42 ] && [ "$(json_field "$config" node_id)" = 9 ] ||
  fail "after a restart the board has target_id $(json_field "$config" target_id), node_id $(json_field "$config" node_id), not 42, 9"
echo "usb: discovery, info, config (persisted across a restart), identify and status over the FunctionFS gadget"
