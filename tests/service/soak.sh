#!/usr/bin/env bash
# soak.sh [FRAMES] [BUILD_DIR]: the service soak run by hand (default 50000 frames, ~1 h on lavapipe at
# 16x9): tiny frames as fast as the device goes, a weather swap every 100 frames, and the daemon's RSS
# and tracked device memory checked flat (same test as the CI soak, which runs 2000 frames).
set -euo pipefail
frames=${1:-50000}
build=${2:-$(dirname "$0")/../../build}
bin=$build/tests/service_e2e_test
[ -x "$bin" ] || { echo "soak.sh: $bin not built (cmake --build $build --target service_e2e_test)"; exit 2; }
SKY_SOAK_FRAMES=$frames exec "$bin" --gtest_filter='ServiceSoak.*'
