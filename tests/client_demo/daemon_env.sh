# SPDX-License-Identifier: MIT
# Sourced by the client_demo end-to-end tests: start_daemon SKYSERVICE DIR starts the real daemon with a
# temporary config (fields of config/service.toml: tiny frames, quality test, render on request, a shadow
# map, its own socket in DIR) and waits for its socket; stop_daemon (call it from the script's EXIT trap)
# stops it (SIGTERM, then wait).
# Exits 77 (ctest: skipped) when the skyservice binary does not yet run the daemon.

daemon_pid=""
stop_daemon() {
    if [ -n "$daemon_pid" ]; then
        kill -TERM "$daemon_pid" 2>/dev/null || true
        wait "$daemon_pid" 2>/dev/null || true
        daemon_pid=""
    fi
}

start_daemon() {
    local skyservice=$1 dir=$2
    if ! "$skyservice" --help 2>/dev/null | grep -q -- "--config"; then
        echo "SKIP: $skyservice does not accept the daemon command line (--config) yet"
        exit 77
    fi
    cat > "$dir/service.toml" <<TOML
[service]
socket_path = "$dir/sky.sock"
files_root = "$dir/frames"
render_rate_hz = 0.0
max_width = 320
max_height = 180
shm_slots = 3
shadow_map_size = 64
shadow_map_extent_m = 100000.0
quality = "test"
log_level = "info"
time = "2026-06-21T10:00:00Z"
rate = 0.0

[service.view]
lat = 44.3
lon = 7.5
alt = 1500.0
width = 160
height = 90
TOML
    "$skyservice" --config "$dir/service.toml" > "$dir/daemon.log" 2>&1 &
    daemon_pid=$!
    for _ in $(seq 1 600); do
        [ -S "$dir/sky.sock" ] && return 0
        if ! kill -0 "$daemon_pid" 2>/dev/null; then
            echo "FAIL: the daemon exited before listening:"; cat "$dir/daemon.log"; daemon_pid=""; exit 1
        fi
        sleep 0.1
    done
    echo "FAIL: no socket after 60 s:"; cat "$dir/daemon.log"; exit 1
}
