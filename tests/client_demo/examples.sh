#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The tiny libskyclient examples (client_demo/examples/, one per transport) against the real daemon:
# each must exit 0 and print the frame it got (shared memory: intact, with a shadow map; Vulkan: the
# imported image's checksum line; files: a PNG that exists and that png_check accepts).
#   examples.sh SKYSERVICE PNG_CHECK EXAMPLE_SHM EXAMPLE_FILES [EXAMPLE_VULKAN]
set -euo pipefail
skyservice=$1 check=$2 shm=$3 files=$4 vulkan=${5:-}
dir=$(mktemp -d /tmp/client_examples_test.XXXXXX)
source "$(dirname "$0")/daemon_env.sh"
cleanup() { stop_daemon; rm -rf "$dir"; }
trap cleanup EXIT
start_daemon "$skyservice" "$dir"

out=$("$shm" --socket "$dir/sky.sock")
echo "$out"
echo "$out" | grep -Eq '^frame [0-9]+: 160x90, mean RGB [0-9.]+, shadow map 64 texels, intact$' ||
    { echo "FAIL: example-shm printed something else"; exit 1; }

mkdir -p "$dir/frames/shots"  # beneath the daemon's files_root (daemon_env.sh)
out=$("$files" --socket "$dir/sky.sock" --root "$dir/frames" --dir shots)
echo "$out"
png=$(echo "$out" | sed -n 's/^frame [0-9]*: \(.*\.png\), [0-9]* bytes$/\1/p')
[ -n "$png" ] && [ -f "$png" ] || { echo "FAIL: example-files named no PNG that exists"; exit 1; }
"$check" "$png" --sky-bluish
[ -f "${png%.png}.json" ] || { echo "FAIL: no JSON sidecar beside $png"; exit 1; }

if [ -n "$vulkan" ]; then
    out=$("$vulkan" "$dir/sky.sock")
    echo "$out"
    echo "$out" | grep -q '^frame [0-9]' || { echo "FAIL: example-vulkan printed no frame line"; exit 1; }
fi
echo "PASS"
