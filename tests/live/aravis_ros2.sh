#!/usr/bin/env bash
# Live test of `localize --camera aravis:127.0.0.1 --ros2` (run inside
# tests/netns/isolated --cyclone: loopback only, Cyclone DDS on lo without multicast).
# The virtual rig's frames come as GVSP packets from fake_rig_camera (no loss); an
# independent ROS 2 reader of rt/tf (reliable, keep last 100, started first) and one
# of rt/tetrapulse/status run beside it. Checks:
#  - every pose of live.csv arrives on rt/tf, in order, parent camera_name, child
#    tetrapulse/target_<id>, translation and rotation equal to 1e-6;
#  - header stamps are on CLOCK_REALTIME: each lies between the wall clock read before
#    the run and after it (rig time as is would be seconds after 1970; rig time taken
#    as CLOCK_MONOTONIC, the host's uptime), and stamp differences are the rig-time
#    differences of live.csv: to 1 ms over the second half, 100 ms over all (the live
#    loop's rig -> host mapping settles on the fastest transfer over the first frames;
#    10 ns measured unloaded);
#  - the last status has the live loop's counters: frames_localized = the frames,
#    frames_matched at least that, frames_dropped the sum of its parts, no queue drop,
#    and a latency on the host's clock (0 < latency_max_ms < 60 s: a clock mix-up
#    would give the uptime).
#   aravis_ros2.sh TETRAPULSE_VISION FAKE_RIG_CAMERA ROS2_LISTENER WORKDIR FRAMES
set -euo pipefail
vision=$1 fake=$2 listener=$3 work=$4 frames=$5
[ "${TETRAPULSE_IN_NETNS:-}" = 1 ] && [ -n "${CYCLONEDDS_URI:-}" ] || { echo "run through tests/netns/isolated --cyclone"; exit 1; }
rm -rf "$work" && mkdir -p "$work"
cd "$work"
"$vision" sim paper-exp1 --out sim --frames 400 >/dev/null
camera_name=$(sed -n 's/^camera_name: *//p' sim/camera.yaml | tr -d '"'"'"'')
pids=()
trap 'for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done' EXIT
"$fake" sim 0 240 > fake.log & pids+=($!)
"$listener" tf --depth 100 --timeout-ms 240000 --out tf.csv > tf.out 2> tf.err & tf=$!; pids+=($tf)
"$listener" status --topic rt/tetrapulse/status --timeout-ms 240000 --out status.csv > status.out 2> status.err & st=$!; pids+=($st)
for _ in $(seq 200); do
  grep -q serving fake.log && grep -qx ready tf.out && grep -qx ready status.out && break
  sleep 0.1
done
grep -q serving fake.log && grep -qx ready tf.out && grep -qx ready status.out || { echo "camera or readers not ready"; cat fake.log tf.err status.err; exit 1; }

before=$(date +%s%N)
timeout 200 "$vision" localize --camera aravis:127.0.0.1 --frames "$frames" --camera-info sim/camera.yaml \
  --targets sim/targets.yaml --camera-clock-is-rig-time --frame-rate 100 --exposure-us 2000 --queue 1024 \
  --out live.csv --ros2 2> localize.err || { cat localize.err; exit 1; }
after=$(date +%s%N)
wait $tf || { echo "tf reader: exit $?"; cat tf.err tf.out; exit 1; }
wait $st || { echo "status reader: exit $?"; cat status.err status.out; exit 1; }
cat localize.err

poses=$(($(wc -l < live.csv) - 1))
[ "$poses" -ge 50 ] || { echo "only $poses live poses"; exit 1; }
[ "$(wc -l < tf.csv)" -eq "$poses" ] || { echo "rt/tf: $(wc -l < tf.csv) transforms for $poses poses"; exit 1; }
# live.csv: frame,timestamp_ns,target,x,y,z,qx,qy,qz,qw,...; tf.csv: sec,nanosec,parent,child,x,y,z,qx,qy,qz,qw
paste -d, <(tail -n +2 live.csv | cut -d, -f1-10) tf.csv | awk -F, -v before="$before" -v after="$after" \
    -v camera="$camera_name" '
  function fail(why) { printf "row %d: %s\n  %s\n", NR, why, $0; bad = 1; exit 1 }
  {
    # Integer nanoseconds exactly: sec * 1e9 + nanosec overflows a double; compare
    # seconds and the rest apart.
    stamp_s = $11; stamp_ns = $12; rig = $2
    if ($13 != camera) fail("parent " $13 " is not " camera)
    if ($14 != "tetrapulse/target_" $3) fail("child " $14)
    for (k = 0; k < 7; ++k) { d = $(4 + k) - $(15 + k); if (d > 1e-6 || d < -1e-6) fail("value " k " differs by " d) }
    if (stamp_s < int(before / 1e9) || stamp_s > int(after / 1e9) + 1) fail("stamp " stamp_s " s is not on CLOCK_REALTIME during the run")
    S[NR] = stamp_s; N[NR] = stamp_ns; R[NR] = rig
  }
  END {
    if (bad) exit 1
    # (stamp - last stamp) - (rig - last rig), in ns (both differences stay well inside
    # a double): the mapping by the fastest transfer seen is settled by the last frame;
    # earlier frames are off by how much slower the fastest transfer then was (on a
    # loaded machine, ms over the first frames), the second half by little.
    for (i = 1; i <= NR; ++i) {
      drift = ((S[i] - S[NR]) * 1e9 + (N[i] - N[NR])) - (R[i] - R[NR])
      if (drift < 0) drift = -drift
      if (drift > worst) worst = drift
      if (i > NR / 2 && drift > late) late = drift
    }
    printf "rt/tf: %d transforms equal to live.csv, stamps on CLOCK_REALTIME; against rig time: worst %.0f ns, second half %.0f ns\n", NR, worst, late
    if (late > 1e6 || worst > 1e8) { print "stamps do not follow rig time"; exit 1 }
  }'

last=$(grep -F ": localizer," status.csv | tail -1)
echo "last status: $last"
value() { echo "$last" | tr ';,' '\n\n' | sed -n "s/^$1=//p"; }
for key in frames_matched frames_localized frames_dropped queue_drops bad_buffers exposures_without_frame \
           frames_without_exposure latency_last_ms latency_mean_ms latency_max_ms; do
  [ -n "$(value $key)" ] || { echo "no $key in the status"; exit 1; }
done
[ "$(value frames_localized)" = "$frames" ] || { echo "frames_localized $(value frames_localized), not $frames"; exit 1; }
# The capture thread may be ahead of the localizer: at least the frames localized.
[ "$(value frames_matched)" -ge "$frames" ] || { echo "frames_matched $(value frames_matched) < $frames"; exit 1; }
# No sync master: dropped = queue drops + bad buffers + frames without an exposure
# (a loaded machine may lose GVSP packets on loopback; the queue of 1024 drops none).
[ "$(value queue_drops)" = 0 ] || { echo "queue_drops $(value queue_drops) with a queue of 1024"; exit 1; }
sum=$(($(value queue_drops) + $(value bad_buffers) + $(value frames_without_exposure)))
[ "$(value frames_dropped)" = "$sum" ] || { echo "frames_dropped $(value frames_dropped), not the parts' $sum"; exit 1; }
bad=$(sed -n 's/.* \([0-9]*\) bad, .*/\1/p' localize.err)
[ "$(value bad_buffers)" -le "${bad:-0}" ] || { echo "bad_buffers $(value bad_buffers) > the summary's $bad"; exit 1; }
awk -v l="$(value latency_max_ms)" 'BEGIN { exit !(l > 0 && l < 60000) }' || { echo "latency_max_ms $(value latency_max_ms) is not on the host clock"; exit 1; }
echo "live --ros2: $poses poses on rt/tf; status frames_matched $(value frames_matched), dropped $(value frames_dropped), latency mean $(value latency_mean_ms) ms, max $(value latency_max_ms) ms"
