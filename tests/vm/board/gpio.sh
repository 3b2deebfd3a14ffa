#!/bin/sh
# gpio-sim: the GPIO sync master and the Linux board's LEDs on simulated lines.
#  - trigger: `tetrapulse sync --trigger` drives a line at 50 Hz; the exposures file has
#    one frame per period and the line's level, sampled through gpio-sim's sysfs, toggles;
#  - strobe: a "camera" pulls a line up and down; `tetrapulse sync --strobe` reports each
#    pulse from kernel line events (CLOCK_MONOTONIC), its width being the exposure;
#  - LEDs: the board plays a code on marker 0; the level sampled through sysfs follows the
#    code (up to its phase: the board runs free here).
set -eu
. /lib/tetrapulse/vm-lib.sh
. /lib/tetrapulse/board-lib.sh

chip=$(gpio_sim_chip board led0 led1 led2 led3 trigger strobe) || fail "cannot create a gpio-sim chip"
trigger_dir=$(gpio_sim_line_dir board 4)
strobe_dir=$(gpio_sim_line_dir board 5)
led0_dir=$(gpio_sim_line_dir board 0)

# Trigger: 25 pulses at 50 Hz, 5 ms wide.
tetrapulse sync --trigger "$chip:trigger" --rate 50 --exposure-us 5000 --frames 25 --out /tmp/trigger.csv >/tmp/trigger.txt 2>&1 &
sync_pid=$!
ones=0
zeros=0
while kill -0 "$sync_pid" 2>/dev/null; do
  read -r level <"$trigger_dir/value" || level=x
  case $level in 1) ones=$((ones + 1)) ;; 0) zeros=$((zeros + 1)) ;; esac
done
wait "$sync_pid" || { cat /tmp/trigger.txt; fail "tetrapulse sync --trigger failed"; }
[ "$ones" -gt 0 ] && [ "$zeros" -gt 0 ] || fail "the trigger line never toggled in sysfs ($ones samples high, $zeros low)"
# Pulse k is due at rig time first + k * 20 ms (the first edge the sync master printed) and
# stamped when the line was set: never before it is due, numbered by its due time. How late
# it comes is the host's wake-up latency (TCG on a loaded machine: milliseconds); reported.
first=$(sed -n 's/.*pulse k rises at rig time \([0-9]*\) + k.*/\1/p' /tmp/trigger.txt)
[ -n "$first" ] || { cat /tmp/trigger.txt; fail "tetrapulse sync --trigger did not say when pulse 0 is due"; }
awk -F, -v first="$first" 'NR == 1 { next }
  { n++; late = $2 - (first + $1 * 20000000); if (late < -100000) early++
    if (n > 1 && $1 <= k) order++; k = $1
    l[n] = late; if (late > max) max = late; sum += late }
  END {
    for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++) if (l[j] < l[i]) { x = l[i]; l[i] = l[j]; l[j] = x }
    printf "trigger: %d exposures; set after due by median %.2f ms, max %.2f ms; %d early, %d out of order\n", n, l[int((n + 1) / 2)] / 1e6, max / 1e6, early, order
    if (n != 25 || early > 0 || order > 0) exit 1
  }' /tmp/trigger.csv || { cat /tmp/trigger.csv; fail "the trigger exposures do not follow the 20 ms grid"; }
echo "trigger: line sampled high $ones times, low $zeros times through sysfs"

# Strobe: 8 pulses of 50 ms, 100 ms apart, from the pull of a simulated input.
echo pull-down >"$strobe_dir/pull"
tetrapulse sync --strobe "$chip:strobe" --rate 10 --frames 8 --out /tmp/strobe.csv >/tmp/strobe.txt 2>&1 &
sync_pid=$!
wait_for 10 sh -c "gpioinfo $chip | grep -q -E 'line +5:.*\"tetrapulse'" || {
  gpioinfo "$chip"
  fail "tetrapulse sync --strobe did not request the strobe line within 10 s"
}
read -r up_start _ </proc/uptime
pulses=0
while [ "$pulses" -lt 10 ] && kill -0 "$sync_pid" 2>/dev/null; do
  echo pull-up >"$strobe_dir/pull"
  usleep 50000
  echo pull-down >"$strobe_dir/pull"
  usleep 50000
  pulses=$((pulses + 1))
done
wait "$sync_pid" || { cat /tmp/strobe.txt; fail "tetrapulse sync --strobe failed"; }
read -r up_end _ </proc/uptime
# Each pulse is high for at least the shell's 50 ms sleep (longer when the loaded VM wakes
# it late); frames are numbered by time at 10 Hz, so a slow "camera" skips numbers.
awk -F, -v t0="${up_start%.*}" -v t1="${up_end%.*}" 'NR == 1 { next }
  { n++; w = $3; if (w < 45000000 || w > 500000000) bad++; s = $2 / 1e9; if (s < t0 - 1 || s > t1 + 1) off++
    if (n > 1 && ($2 <= t || $1 <= k)) order++; t = $2; k = $1; sum += w }
  END {
    printf "strobe: %d exposures from kernel edge stamps, mean width %.1f ms (pulses held >= 50 ms), %d widths outside 45..500 ms, %d stamps outside the run (monotonic %d..%d s), %d out of order\n", n, sum / n / 1e6, bad, off, t0, t1, order
    if (n != 8 || bad > 0 || off > 0 || order > 0) exit 1
  }' /tmp/strobe.csv || { cat /tmp/strobe.csv; fail "the strobe exposures do not match the pulses"; }

# LEDs: the board on vcan1 (its configuration link), marker 0 playing 1100101000 at 100 ms bits.
ip link add dev vcan1 type vcan || fail "cannot create vcan1"
ip link set up vcan1
tetrapulse-board image --fw-version 1.0.0 --payload-size 4096 --out /tmp/gpio-v1.img
trap 'board_stop' EXIT
board_start /tmp/board-gpio.txt --flash /tmp/gpio-flash.bin --factory-image /tmp/gpio-v1.img --node 5 --can vcan1 \
  --led "$chip:led0" --led "$chip:led1" --led "$chip:led2" --led "$chip:led3" --report-clock ||
  fail "the board did not start with LEDs on $chip"
gpioinfo "$chip" | grep -q -E 'line +0:.*"tetrapulse-board" +output' || { gpioinfo "$chip"; fail "the board does not hold led0 as an output"; }
tetrapulse config --can vcan1:5 --modulation on_off --bit-period-ns 100000000 --code 0=1100101000 ||
  fail "tetrapulse config of marker 0's code failed"
sleep 1
read -r up _ </proc/uptime
end=$((${up%.*} + 4))
: >/tmp/led0.txt
while :; do
  read -r up _ </proc/uptime
  [ "${up%.*}" -lt "$end" ] || break
  read -r level <"$led0_dir/value"
  echo "$up $level" >>/tmp/led0.txt
done
# The best cyclic phase of the code against the samples (10 ms steps): the share of
# samples that match it, away from bit boundaries (a sample time is good to 10 ms).
awk -v code=1100101000 '
  { t[NR] = int($1 * 100 + 0.5); v[NR] = $2 }
  END {
    best = 0
    for (p = 0; p < 100; p++) {
      good = 0; used = 0
      for (i = 1; i <= NR; i++) {
        x = (t[i] - p) % 100; if (x < 0) x += 100
        if (x % 10 == 0 || x % 10 == 9) continue
        used++; if (substr(code, int(x / 10) + 1, 1) == v[i]) good++
      }
      if (used > 0 && good / used > best) { best = good / used; phase = p }
    }
    printf "leds: %d sysfs samples of led0 over 4 s; best phase %d0 ms matches %.1f%% of them\n", NR, phase, 100 * best
    if (NR < 100 || best < 0.95) exit 1
  }' /tmp/led0.txt || { head -50 /tmp/led0.txt; fail "led0 does not play 1100101000 at 100 ms bits"; }
grep ' clock ' /tmp/board-gpio.txt | tail -1
