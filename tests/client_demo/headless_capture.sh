#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# client_demo --headless against the real daemon: 3 frames of the scripted flight through libskyclient;
# each PNG must exist, be neither uniform nor black, and show a bluish sky; each JSON sidecar must name its
# frame, and the flight must move (the views of the first and last frame differ).
#   headless_capture.sh SKYSERVICE CLIENT_DEMO PNG_CHECK TRANSPORT
set -euo pipefail
skyservice=$1 demo=$2 check=$3 transport=$4
dir=$(mktemp -d /tmp/client_demo_test.XXXXXX)
source "$(dirname "$0")/daemon_env.sh"
cleanup() { stop_daemon; rm -rf "$dir"; }
trap cleanup EXIT
start_daemon "$skyservice" "$dir"

"$demo" --socket "$dir/sky.sock" --headless --frames 3 --out "$dir/out" --width 160 --height 90 \
    --transport "$transport" --frame-timeout-ms 60000
for i in 0000 0001 0002; do
    "$check" "$dir/out/frame-$i.png" --sky-bluish
    grep -q '"frame_id"' "$dir/out/frame-$i.json" || { echo "FAIL: frame-$i.json has no frame_id"; exit 1; }
    grep -q "\"transport\": \"$transport\"" "$dir/out/frame-$i.json" || { echo "FAIL: frame-$i.json: not $transport"; exit 1; }
done
if [ "$(grep -A8 '"view"' "$dir/out/frame-0000.json")" = "$(grep -A8 '"view"' "$dir/out/frame-0002.json")" ]; then
    echo "FAIL: the scripted flight did not move the view"; exit 1
fi
ls "$dir"/out/*.tmp* 2>/dev/null && { echo "FAIL: temporary files left behind"; exit 1; }
echo "PASS"
