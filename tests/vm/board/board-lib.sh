# Helpers for the Linux board's VM tests (busybox sh), installed as
# /lib/tetrapulse/board-lib.sh beside vm-lib.sh.  . /lib/tetrapulse/board-lib.sh

BOARD_SERIAL=0123456789ABCDEF01234567
BOARD_GADGET=tp

# board_start LOG ARG...: starts tetrapulse-board with ARG... in the background, its
# output in LOG, and waits until it runs its application or its DFU bootloader.
board_start() {
  board_log_file=$1
  shift
  tetrapulse-board "$@" >"$board_log_file" 2>&1 &
  echo "$!" >/run/board.pid
  if ! wait_for 20 grep -q -e '] application ' -e 'bootloader: DFU mode' "$board_log_file"; then
    cat "$board_log_file"
    return 1
  fi
}

# board_usb_args FLASH: the arguments of a USB board with its flash in FLASH.
board_usb_args() {
  echo "--flash $1 --serial $BOARD_SERIAL --usb-gadget $BOARD_GADGET --usb-mount /dev/ffs/$BOARD_GADGET"
}

# board_start_can NAME: vcan0 up and a board on it as node 3, its clock 40 ppm fast and
# reported every second, with its log in /tmp/board-NAME.txt and its flash in
# /tmp/NAME-flash.bin (factory image 1.0.0).
board_start_can() {
  ip link del dev vcan0 2>/dev/null || :  # an earlier script of the same boot left it
  ip link add dev vcan0 type vcan || fail "cannot create vcan0"
  ip link set up vcan0
  tetrapulse-board image --fw-version 1.0.0 --payload-size 4096 --out "/tmp/$1-v1.img"
  board_start "/tmp/board-$1.txt" --flash "/tmp/$1-flash.bin" --factory-image "/tmp/$1-v1.img" --node 3 \
    --can vcan0 --clock-ppm 40 --report-clock || fail "the board did not start on vcan0"
}

# board_stop: ends the board and removes its gadget. Safe under set -e, for EXIT traps.
board_stop() {
  if [ -f /run/board.pid ]; then
    kill "$(cat /run/board.pid)" 2>/dev/null || :
    wait "$(cat /run/board.pid)" 2>/dev/null || :
    rm -f /run/board.pid
  fi
  usb_gadget_remove "$BOARD_GADGET"
}

# board_count LOG PATTERN: how many lines of LOG match PATTERN.
board_count() {
  grep -c -e "$2" "$1" || :
}

# json_field JSON NAME: the value of "NAME" in a one-line JSON object (string quotes dropped).
json_field() {
  echo "$1" | sed -n "s/.*\"$2\": *\"\{0,1\}\([^\",}]*\).*/\1/p"
}

# board_wait_version VERSION TRIES: until `tetrapulse info` over USB reports VERSION
# (one try a second at most).
board_wait_version() {
  board_tries=$2
  while [ "$board_tries" -gt 0 ]; do
    [ "$(json_field "$(tetrapulse info --usb "$BOARD_SERIAL" --json 2>/dev/null)" fw_version)" = "$1" ] && return 0
    sleep 1
    board_tries=$((board_tries - 1))
  done
  return 1
}
