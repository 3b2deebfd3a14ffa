#!/usr/bin/env bash
# Live test (run inside tests/netns/isolated): Debian's fake GigE Vision camera on
# 127.0.0.1 with 1 % of GVSP packets lost; `tetrapulse record` through it writes a
# dataset that passes the contract, and one killed with SIGKILL mid-recording leaves
# a dataset of the frames written so far (`localize --camera`: aravis_virtual_rig.sh).
#   aravis_record.sh TETRAPULSE_VISION RIG_DATASET_CHECK WORKDIR
set -euo pipefail
vision=$1 check=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
cd "$work"
"$vision" sim paper-exp1 --out sim --frames 2 >/dev/null
arv-fake-gv-camera-0.8 -i 127.0.0.1 -r 10 & camera=$!
trap 'kill $camera 2>/dev/null || true' EXIT
# The fake camera answers once it listens; record retries nothing, so wait for its port.
for _ in $(seq 50); do ss -lun 2>/dev/null | grep -q ':3956 ' && break; sleep 0.1; done
rc=0
timeout 120 "$vision" record --camera aravis:127.0.0.1 --frames 30 --camera-info sim/camera.yaml \
  --targets sim/targets.yaml --out rec --pixel-format Mono8 --frame-rate 30 || rc=$?
 [ $rc -eq 0 ] || [ $rc -eq 8 ] || exit $rc   # 8: bad buffers were skipped (counted)
"$check" rec 30
# A recording killed outright (SIGKILL: no handler, nothing finished) is still a
# dataset holding every frame written before the kill (frames.csv grows row by row).
timeout 120 "$vision" record --camera aravis:127.0.0.1 --frames 0 --camera-info sim/camera.yaml \
  --targets sim/targets.yaml --out killed --pixel-format Mono8 --frame-rate 30 --quiet & recorder=$!
rows=0
for _ in $(seq 600); do   # at most 60 s for 6 rows (30 fps: about 0.2 s unloaded)
  [ -f killed/frames.csv ] && rows=$(($(wc -l < killed/frames.csv) - 1))
  [ "$rows" -ge 6 ] && break
  sleep 0.1
done
kill -KILL "$recorder" 2>/dev/null || true
wait "$recorder" 2>/dev/null || true
[ "$rows" -ge 6 ] || { echo "aravis_record.sh: only $rows rows in killed/frames.csv before the kill" >&2; exit 1; }
"$check" killed 6
