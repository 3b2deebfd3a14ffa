# Helpers for test scripts inside the tetrapulse test VM (busybox sh).
# A test sources it:  . /lib/tetrapulse/vm-lib.sh

# fail MESSAGE: ends the test with a failure that says what was wrong.
fail() {
  echo "FAIL: $*"
  exit 1
}

# wait_for SECONDS COMMAND...: polls COMMAND every 0.1 s until it succeeds; fails after SECONDS.
wait_for() {
  wait_limit=$1
  shift
  wait_ticks=$((wait_limit * 10))
  while ! "$@" >/dev/null 2>&1; do
    wait_ticks=$((wait_ticks - 1))
    [ "$wait_ticks" -gt 0 ] || return 1
    usleep 100000
  done
}

# v4l2_node NAME: prints /dev/videoN of the V4L2 node whose sysfs name is NAME
# (vivid: vivid-000-vid-cap, vivid-000-vid-out, vivid-000-meta-cap); fails when none is.
v4l2_node() {
  for v4l2_dir in /sys/class/video4linux/video*; do
    [ "$(cat "$v4l2_dir/name" 2>/dev/null)" = "$1" ] && { echo "/dev/$(basename "$v4l2_dir")"; return 0; }
  done
  return 1
}

# gpio_sim_chip NAME LINE_NAME...: a live gpio-sim chip with one bank, one line
# per name. Prints the chip's gpiochipN name. Its sysfs lines are
# /sys/devices/platform/<dev_name>/<gpiochipN>/sim_gpio<K>/{value,pull}.
gpio_sim_chip() {
  chip_dir=/sys/kernel/config/gpio-sim/$1
  shift
  mkdir "$chip_dir" "$chip_dir/bank0" || return 1
  echo "$#" >"$chip_dir/bank0/num_lines"
  line=0
  for line_name in "$@"; do
    mkdir "$chip_dir/bank0/line$line"
    echo "$line_name" >"$chip_dir/bank0/line$line/name"
    line=$((line + 1))
  done
  echo 1 >"$chip_dir/live"
  cat "$chip_dir/bank0/chip_name"
}

# gpio_sim_line_dir NAME OFFSET: sysfs directory of a line of the chip NAME.
gpio_sim_line_dir() {
  chip_dir=/sys/kernel/config/gpio-sim/$1
  echo "/sys/devices/platform/$(cat "$chip_dir/dev_name")/$(cat "$chip_dir/bank0/chip_name")/sim_gpio$2"
}

# usb_gadget_ffs NAME VID PID: a configfs gadget with one FunctionFS function,
# its ep0 mounted at /dev/ffs/NAME. Not yet bound: a program must write its
# descriptors to /dev/ffs/NAME/ep0 first, then usb_gadget_bind.
usb_gadget_ffs() {
  gadget=/sys/kernel/config/usb_gadget/$1
  mkdir "$gadget" || return 1
  echo "$2" >"$gadget/idVendor"
  echo "$3" >"$gadget/idProduct"
  mkdir "$gadget/strings/0x409"
  echo tetrapulse >"$gadget/strings/0x409/manufacturer"
  echo "$1" >"$gadget/strings/0x409/product"
  echo "vm-$1" >"$gadget/strings/0x409/serialnumber"
  mkdir "$gadget/configs/c.1" "$gadget/functions/ffs.$1"
  echo 100 >"$gadget/configs/c.1/MaxPower"
  ln -s "$gadget/functions/ffs.$1" "$gadget/configs/c.1/"
  mkdir -p "/dev/ffs/$1"
  mount -t functionfs "$1" "/dev/ffs/$1"
}

# usb_gadget_bind NAME: attaches the gadget to the (only) UDC, dummy_udc.0.
usb_gadget_bind() {
  ls /sys/class/udc | head -1 >"/sys/kernel/config/usb_gadget/$1/UDC"
}

# usb_gadget_start NAME VID PID LOG READY PROGRAM [ARG...]: the whole bring-up.
# Creates the gadget (usb_gadget_ffs), starts PROGRAM in the background with
# its output in LOG, waits until LOG shows READY (the program has written its
# descriptors to ep0), binds, and waits until the host side enumerates VID:PID.
# Returns 1 when a step does not happen within 20 s; LOG then tells why.
usb_gadget_start() {
  gadget_name=$1 gadget_vid=${2#0x} gadget_pid=${3#0x} gadget_log=$4 gadget_ready=$5
  shift 5
  usb_gadget_ffs "$gadget_name" "0x$gadget_vid" "0x$gadget_pid" || return 1
  "$@" >"$gadget_log" 2>&1 &
  echo "$!" >"/run/usb-gadget-$gadget_name.pid"
  wait_for 20 sh -c "grep -q '$gadget_ready' '$gadget_log' || ! kill -0 $!" || :
  grep -q "$gadget_ready" "$gadget_log" || return 1
  usb_gadget_bind "$gadget_name" || return 1
  wait_for 20 lsusb -d "$gadget_vid:$gadget_pid"
}

# usb_gadget_stop NAME: ends the program usb_gadget_start started and removes
# the gadget. Safe under set -e, for EXIT traps.
usb_gadget_stop() {
  if [ -f "/run/usb-gadget-$1.pid" ]; then
    kill "$(cat "/run/usb-gadget-$1.pid")" 2>/dev/null || :
    wait "$(cat "/run/usb-gadget-$1.pid")" 2>/dev/null || :
    rm -f "/run/usb-gadget-$1.pid"
  fi
  usb_gadget_remove "$1"
}

# usb_gadget_remove NAME: unbinds and deletes the gadget, so another test can
# bind. Stop the program holding ep0 first. Safe under set -e, for EXIT traps.
usb_gadget_remove() {
  gadget=/sys/kernel/config/usb_gadget/$1
  [ -d "$gadget" ] || return 0
  echo "" >"$gadget/UDC" 2>/dev/null || :
  rm -f "$gadget/configs/c.1/ffs.$1" || :
  umount "/dev/ffs/$1" 2>/dev/null || :
  rmdir "$gadget/configs/c.1" "$gadget/functions/ffs.$1" "$gadget/strings/0x409" "$gadget" 2>/dev/null || :
}
