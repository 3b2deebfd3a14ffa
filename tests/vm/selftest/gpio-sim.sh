#!/bin/sh
# gpio-sim: a live configfs chip with 8 named lines. An output driven with
# gpioset shows in sysfs; an input driven through sysfs pull makes gpiomon
# report rising and falling edges with kernel timestamps.
set -eu
. /lib/tetrapulse/vm-lib.sh

chip=$(gpio_sim_chip selftest sync_in strobe_out led0 led1 led2 led3 trigger spare) ||
  fail "cannot create a gpio-sim chip through configfs"
gpiodetect
gpioinfo "$chip"
[ "$(gpiofind strobe_out)" = "$chip 1" ] || fail "line name strobe_out not found on $chip (gpiofind: '$(gpiofind strobe_out)')"
[ "$(gpiodetect | grep -c "^$chip ")" -eq 1 ] || fail "$chip is not listed by gpiodetect"
gpioinfo "$chip" | grep -q -E 'line +7: +"spare"' || fail "line 7 is not named spare"

# Output: the level gpioset drives is what the simulator's sysfs shows.
out=$(gpio_sim_line_dir selftest 1)
echo "output line sysfs: $out"
for level in 1 0 1; do
  gpioset --mode=signal "$chip" 1="$level" &
  holder=$!
  wait_for 10 sh -c "[ \"\$(cat $out/value)\" = $level ]" || fail "strobe_out set to $level but $out/value reads $(cat "$out/value")"
  kill "$holder"
  wait "$holder" 2>/dev/null || true
done
echo "gpio-sim: output levels 1, 0, 1 seen in $out/value"

# Input: a pull change is an edge with a kernel timestamp.
in=$(gpio_sim_line_dir selftest 0)
echo pull-down >"$in/pull"
gpiomon --num-events=2 --format='%e %o %s %n' "$chip" 0 >/tmp/gpiomon.txt 2>&1 &
monitor=$!
# gpiomon starts slowly under TCG; edges count once it has requested the line.
wait_for 10 sh -c "gpioinfo $chip | grep -q -E 'line +0:.*\"gpiomon\"'" || fail "gpiomon did not request line 0 within 10 s"
read -r up_mono _ </proc/uptime
up_real=$(date +%s)
echo pull-up >"$in/pull"
sleep 0.2
echo pull-down >"$in/pull"
wait_for 10 sh -c "! kill -0 $monitor" || fail "gpiomon reported $(wc -l </tmp/gpiomon.txt) of 2 edges within 10 s"
cat /tmp/gpiomon.txt
# shellcheck disable=SC2046 # split into fields on purpose
set -- $(cat /tmp/gpiomon.txt)
[ "$#" -eq 8 ] || fail "gpiomon printed '$*', not two events"
[ "$1 $2" = "1 0" ] && [ "$5 $6" = "0 0" ] || fail "events are '$1 $2' and '$5 $6', not rising then falling on line 0"
rise=$3$(printf '%09d' "$4")
fall=$7$(printf '%09d' "$8")
[ "$3" -gt 0 ] || fail "the rising edge has no timestamp"
[ "$fall" -gt "$rise" ] || fail "falling edge ($7.$8) is not after the rising edge ($3.$4)"
mono=${up_mono%.*}
if [ $(($3 - mono)) -ge -1 ] && [ $(($3 - mono)) -le 5 ]; then
  clock=CLOCK_MONOTONIC
elif [ $(($3 - up_real)) -ge -1 ] && [ $(($3 - up_real)) -le 5 ]; then
  clock=CLOCK_REALTIME
else
  fail "edge timestamp $3 s matches neither the monotonic clock ($mono s) nor the wall clock ($up_real s)"
fi
echo "gpio-sim: edges rising $3.$4, falling $7.$8 ($(((fall - rise) / 1000000)) ms apart), timestamps on $clock"

# After the monitor, the input reads the pulled level.
echo pull-up >"$in/pull"
[ "$(gpioget "$chip" 0)" = 1 ] || fail "input pulled up reads $(gpioget "$chip" 0)"
echo pull-down >"$in/pull"
[ "$(gpioget "$chip" 0)" = 0 ] || fail "input pulled down reads $(gpioget "$chip" 0)"
echo "gpio-sim: input follows pull-up/pull-down"
