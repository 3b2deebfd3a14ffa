# V4L2 frames that travelled through a kernel driver and back: vivid's HDMI
# output looped to its HDMI input (vivid_loop_probe connect/send), recorded by
# `tetrapulse record --camera v4l2:DEV`, stopped by SIGINT. The recording must
# hold every frame sent, byte for byte, in order, none lost (repeats are the
# capture seeing one output frame twice), with strictly increasing exposure
# stamps, and pass the contract.
set -eu
. /lib/tetrapulse/vm-lib.sh

cap=$(v4l2_node vivid-000-vid-cap) || fail "vivid loaded no video capture node"
out=$(v4l2_node vivid-000-vid-out) || fail "vivid loaded no video output node"
echo "vivid capture $cap, output $out"

work=/tmp/vivid-loop
mkdir -p $work/sent
count=20
tetrapulse sim paper-exp1 --frames $((count + 2)) --out $work/sim >/dev/null
sed 's/^image_width: .*/image_width: 640/' $work/sim/camera.yaml > $work/camera.yaml

vivid_loop_probe connect --capture "$cap" || fail "cannot set up the loop on $cap"
tetrapulse record --camera "v4l2:$cap" --pixel-format Mono8 --camera-info $work/camera.yaml \
  --targets $work/sim/targets.yaml --out $work/rec > $work/record.log 2>&1 &
rec_pid=$!
# The recorder streams (vivid's test pattern, until the output starts) before anything is sent.
wait_for 60 sh -c "ls $work/rec/frames 2>/dev/null | grep -q png" || { cat $work/record.log; fail "record wrote no frame within 60 s"; }
# --await: each frame stays on show until the recording holds it (the recorder may
# fall behind for seconds on the emulated machine; its queue then drops what it cannot write).
timeout 150 vivid_loop_probe send --output "$out" --dataset $work/sim --count $count --hold 12 --lead 20 --trail 30 \
  --sent $work/sent --await $work/rec || { kill -INT $rec_pid; fail "streaming to $out failed"; }
kill -INT $rec_pid
rc=0
wait $rec_pid || rc=$?
cat $work/record.log
[ "$rc" -eq 0 ] || fail "record exited $rc after SIGINT"
rig_dataset_check $work/rec 1 || fail "the recording breaks the contract"
vivid_loop_probe check --sent $work/sent --count $count --recording $work/rec || fail "the frames recorded are not the frames sent"
