#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# client_demo --composite layers against the real daemon: 2 frames of the scripted flight (160x90) over
# shared memory with the sky, clouds and depth layers, the demo's mountain composited by depth. The eye
# flies at 800 m, nose 8 degrees up (the horizon below the text overlay), under cumulus whose bases lie
# between it and the mountain 12 km ahead: the mountain's foot is in front of the clouds, its upper part
# behind them. The same flight is captured again with --composite display (the flat ground over the
# finished frame, no mountain) as the reference: where the mountain stands above the horizon the layers
# picture must be darker than the display picture's hazy sky, and the sidecars must say which path ran
# and that terrain was drawn both in front of and behind clouds. The layers flight is flown over both
# transports: over the Vulkan one (the layers exported as images, imported by the demo) the terrain must lie
# in front of and behind clouds in exactly the same pixels as over shared memory (the pictures differ only
# in the overlay's frame id and transport).
#   headless_layers.sh SKYSERVICE CLIENT_DEMO PNG_CHECK
set -euo pipefail
skyservice=$1 demo=$2 check=$3
dir=$(mktemp -d /tmp/client_demo_layers.XXXXXX)
source "$(dirname "$0")/daemon_env.sh"
cleanup() { stop_daemon; rm -rf "$dir"; }
trap cleanup EXIT
start_daemon "$skyservice" "$dir"

for run in layers:shm layers-vulkan:vulkan display:auto; do
    out=${run%%:*} transport=${run##*:}
    "$demo" --socket "$dir/sky.sock" --headless --frames 2 --out "$dir/$out" --width 160 --height 90 \
        --alt 800 --pitch 8 --composite "${out%%-*}" --transport "$transport" --frame-timeout-ms 60000
done
for i in 0000 0001; do
    json="$dir/layers/frame-$i.json"
    grep -q '"composite": "layers"' "$json" || { echo "FAIL: $json: not composited by layers"; cat "$json"; exit 1; }
    grep -q '"transport": "shm"' "$json" || { echo "FAIL: $json: not over shared memory"; exit 1; }
    vjson="$dir/layers-vulkan/frame-$i.json"
    grep -q '"composite": "layers"' "$vjson" && grep -q '"transport": "vulkan"' "$vjson" ||
        { echo "FAIL: $vjson: not composited by layers over the vulkan transport"; cat "$vjson"; exit 1; }
    count() { sed -n "s/.*\"$1\": \([0-9]*\).*/\1/p" "${2:-$json}"; }
    pixels=$(count pixels) front=$(count in_front_of_cloud_pixels) behind=$(count behind_cloud_pixels)
    for what in pixels in_front_of_cloud_pixels behind_cloud_pixels; do
        [ "$(count $what)" = "$(count $what "$vjson")" ] ||
            { echo "FAIL: frame $i: $what over vulkan $(count $what "$vjson"), over shm $(count $what)"; exit 1; }
    done
    echo "$json: terrain ${pixels:-0} px, ${front:-0} in front of clouds, ${behind:-0} behind them"
    # The mountain and the flat ground fill ~6000 of the 14400 pixels; ~500 lie in front of a cloud, ~300
    # behind one.
    [ "${pixels:-0}" -gt 3000 ] || { echo "FAIL: $json: terrain in ${pixels:-0} pixels"; exit 1; }
    [ "${front:-0}" -gt 100 ] && [ "${behind:-0}" -gt 100 ] ||
        { echo "FAIL: $json: the terrain is not both in front of and behind clouds"; exit 1; }
    grep -q '"composite": "display"' "$dir/display/frame-$i.json" || { echo "FAIL: display run not display"; exit 1; }
    "$check" "$dir/layers/frame-$i.png" --sky-bluish
    # The main peak's lower flanks (forest, 12 km ahead): columns 64..104, rows 52..58 (the horizon is row
    # ~60); in the display path those pixels are hazy sky (mean luma ~170 there, ~125 on the mountain).
    "$check" "$dir/layers/frame-$i.png" --darker-than "$dir/display/frame-$i.png" 64 52 104 58 0.85
    "$check" "$dir/layers-vulkan/frame-$i.png" --darker-than "$dir/display/frame-$i.png" 64 52 104 58 0.85
done
ls "$dir"/layers/*.tmp* 2>/dev/null && { echo "FAIL: temporary files left behind"; exit 1; }
echo "PASS"
