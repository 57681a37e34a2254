#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# client_demo's window under Xvfb (lavapipe presents to X11 surfaces): 3 service frames shown, then the
# last presented swapchain image read back (--screenshot) must be neither black nor uniform.
#   windowed_xvfb.sh SKYSERVICE CLIENT_DEMO PNG_CHECK
set -euo pipefail
skyservice=$1 demo=$2 check=$3
if ! command -v xvfb-run >/dev/null; then
    echo "SKIP: xvfb-run is not installed (apt-get install xvfb xauth)"; exit 77
fi
dir=$(mktemp -d /tmp/client_demo_test.XXXXXX)
source "$(dirname "$0")/daemon_env.sh"
cleanup() { stop_daemon; rm -rf "$dir"; }
trap cleanup EXIT
start_daemon "$skyservice" "$dir"

xvfb-run -a -s "-screen 0 640x480x24" "$demo" --socket "$dir/sky.sock" --frames 3 --width 160 --height 90 \
    --screenshot "$dir/shot.png" --frame-timeout-ms 60000
"$check" "$dir/shot.png" --sky-bluish
echo "PASS"
