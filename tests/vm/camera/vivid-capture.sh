# V4L2 capture through a real kernel driver: Debian's vivid (drivers/media/
# test-drivers/vivid) in the VM, its video capture node opened by
# `tetrapulse record --camera v4l2:DEV`. 30 frames are written, the dataset
# passes the contract (rig_dataset_check: frame numbers and exposure starts
# strictly increasing, every image there and camera-sized), and a camera.yaml
# of the wrong size is refused frame by frame with the sizes named, never written.
set -eu
. /lib/tetrapulse/vm-lib.sh

cap=$(v4l2_node vivid-000-vid-cap) || fail "vivid loaded no video capture node"
echo "vivid capture node: $cap"

work=/tmp/vivid
mkdir -p $work
tetrapulse sim paper-exp1 --frames 1 --out $work/sim >/dev/null
# vivid's default webcam input gives 640x480.
sed 's/^image_width: .*/image_width: 640/' $work/sim/camera.yaml > $work/camera.yaml

timeout 120 tetrapulse record --camera "v4l2:$cap" --frames 30 --camera-info $work/camera.yaml \
  --targets $work/sim/targets.yaml --out $work/rec || fail "record exited $?"
rig_dataset_check $work/rec 30 || fail "the recording breaks the contract"
rows=$(($(wc -l < $work/rec/frames.csv) - 1))
[ "$rows" -eq 30 ] || fail "30 frames asked, $rows written"

# A camera.yaml that says 752x480: every frame is skipped with both sizes named.
rc=0
timeout 60 tetrapulse record --camera "v4l2:$cap" --frames 3 --camera-info $work/sim/camera.yaml \
  --targets $work/sim/targets.yaml --out $work/wrong > $work/wrong.log 2>&1 || rc=$?
cat $work/wrong.log
[ "$rc" -eq 8 ] || fail "the mismatched run exited $rc, not 8 (frames skipped)"
grep -q "640x480 image, camera.yaml says 752x480" $work/wrong.log || fail "the size mismatch was not named"
[ "$(($(wc -l < $work/wrong/frames.csv) - 1))" -eq 0 ] || fail "frames of the wrong size were written"

# The host cannot trigger a V4L2 camera: --sync-trigger is refused before any frame,
# naming why (its stamps would not be the host's pulses).
chip=$(gpio_sim_chip trig trigger) || fail "cannot create a gpio-sim chip"
rc=0
timeout 60 tetrapulse record --camera "v4l2:$cap" --sync-trigger "$chip:0" --frame-rate 15 --frames 3 \
  --camera-info $work/camera.yaml --targets $work/sim/targets.yaml --out $work/trig > $work/trig.log 2>&1 || rc=$?
cat $work/trig.log
[ "$rc" -ne 0 ] || fail "record --sync-trigger on a V4L2 camera succeeded"
grep -q "V4L2 has no hardware trigger" $work/trig.log || fail "the refusal does not say why"
echo "vivid capture: 30 frames recorded; the mismatched camera.yaml refused; --sync-trigger refused"
