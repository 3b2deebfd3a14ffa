#!/usr/bin/env bash
# Live test (run inside tests/netns/isolated): the virtual rig's frames served as GVSP
# packets by fake_rig_camera (LOST per thousand packets lost, packet resend answered
# unless RESEND is "no"), localized live with `localize --camera aravis:127.0.0.1
# --record --overlay`; then the recorded frames (the ones that arrived) localized offline.
# Checks: the live poses equal the offline run's byte for byte; against the rig's
# ground truth (live rows mapped to the rig's frames by their exposure stamps):
# 0 misidentified rows and every target of targets.yaml identified; at least
# MIN_COMPLETE % of the frames sent within the run arrived complete.
#   aravis_virtual_rig.sh TETRAPULSE_VISION FAKE_RIG_CAMERA WORKDIR LOST FRAMES MIN_COMPLETE [RESEND]
set -euo pipefail
vision=$1 fake=$2 work=$3 lost=$4 frames=$5 min_complete=$6 resend=${7:-yes}
rm -rf "$work" && mkdir -p "$work"
cd "$work"
"$vision" sim paper-exp1 --out sim --frames 400 >/dev/null
flag=()
[ "$resend" = yes ] || flag=(--no-resend)
"$fake" sim "$lost" 240 "${flag[@]}" > fake.log & camera=$!
trap 'kill $camera 2>/dev/null || true' EXIT
for _ in $(seq 100); do grep -q serving fake.log && break; sleep 0.1; done
# Exit 1 (nothing identified) only counts as a failure below, with the figures printed.
live=0
timeout 200 "$vision" localize --camera aravis:127.0.0.1 --frames "$frames" --camera-info sim/camera.yaml \
  --targets sim/targets.yaml --camera-clock-is-rig-time --frame-rate 100 --exposure-us 2000 --queue 1024 \
  --record rec --out live.csv --overlay live.avi 2> live.log || live=$?
cat live.log
grep -q "overlay video: $frames frames written to live.avi" live.log || { echo "no overlay video of $frames frames"; exit 1; }
kill -TERM $camera && wait $camera || true
trap - EXIT
cat fake.log
[ $live -eq 0 ] || [ $live -eq 1 ] || { echo "localize --camera exited $live"; exit 1; }
off=0
"$vision" localize rec --out offline.csv --quiet || off=$?
[ $off -eq 0 ] || [ $off -eq 1 ] || { echo "offline localize exited $off"; exit 1; }
cmp live.csv offline.csv && equal=yes || equal=no

# The rig frame of each recorded frame, by its exposure stamp (the fake camera stamps
# frames with the rig's own), and so of each live row.
awk -F, -v OFS=, 'FILENAME == ARGV[1] { if (FNR > 1) rig[$2] = $1; next }
  FILENAME == ARGV[2] { if (FNR > 1) { if (!($2 in rig)) { print "rec frame " $1 ": stamp " $2 " is no rig frame" > "/dev/stderr"; bad = 1 } of[$1] = rig[$2] } next }
  FNR == 1 { print; next } { $1 = of[$1]; print } END { exit bad }' sim/frames.csv rec/frames.csv live.csv > live_rig_frames.csv
arrived=$(($(wc -l < rec/frames.csv) - 1))
read -r first last < <(awk -F, 'NR == FNR { if (FNR > 1) rig[$2] = $1; next } FNR > 1 { k = rig[$2]; if (min == "" || k < min) min = k; if (k > max) max = k } END { print min, max }' \
  sim/frames.csv rec/frames.csv)
sent=$((last - first + 1))
"$vision" eval sim live_rig_frames.csv > eval.txt || true
cat eval.txt
misidentified=$("$vision" eval sim live_rig_frames.csv --json | python3 -c 'import json,sys; print(json.load(sys.stdin)["overall"]["misidentified"])')
missing=""
for id in $(grep -E '^\s*- id:' sim/targets.yaml | sed 's/.*id: *//'); do
  n=$(tail -n +2 live.csv | awk -F, -v id="$id" '$3 == id' | wc -l)
  identified+=" target $id in $n frames"
  [ "$n" -gt 0 ] || missing+=" $id"
done
echo "packet loss ${lost}/1000, resend $resend: frames sent $sent (rig frames $first..$last), arrived complete $arrived" \
  "($((100 * arrived / sent)) %); identified:$identified; misidentified $misidentified; poses equal to the offline run" \
  "on the frames that arrived: $equal"
[ "$equal" = yes ]
[ "$misidentified" -eq 0 ]
[ -z "$missing" ] || { echo "never identified: target$missing"; exit 1; }
[ $((100 * arrived)) -ge $((min_complete * sent)) ] || { echo "fewer than $min_complete % of the frames arrived complete"; exit 1; }
