# cmake -DJSON=FILE -DFRAMES=N -DSECONDS=S -P check_flight_json.cmake: checks the shape and the internal
# consistency of sky-service-bench --flight-path's JSON: N frames over S simulated seconds, some per
# second, ordered frame times, the slowest second within the path with its pose and the daemon's per-pass
# means, every frame's daemon times read, and the eye entering and leaving the built-in cumulus layer
# (1200..3200 m, climbing 15 m/s from 300 m: from 60 s to 193 s).
file(READ ${JSON} doc)
macro(get var)
    string(JSON ${var} ERROR_VARIABLE err GET "${doc}" ${ARGN})
    if(err)
        message(FATAL_ERROR "${JSON}: ${ARGN}: ${err}")
    endif()
endmacro()
macro(expect condition)
    if(NOT (${ARGN}))
        message(FATAL_ERROR "${JSON}: expected ${condition}")
    endif()
endmacro()

get(mode mode)
expect("mode flight-path, got ${mode}" mode STREQUAL "flight-path")
get(deviceName device name)
expect("a device name" deviceName MATCHES ".")
get(frames frames)
expect("${FRAMES} frames, got ${frames}" frames EQUAL FRAMES)
get(fps fps)
expect("frames per second > 0, got ${fps}" fps GREATER 0)
get(median frameMs median)
get(p99 frameMs p99)
get(max frameMs max)
expect("0 < median ${median} <= p99 ${p99} <= max ${max}" median GREATER 0 AND median LESS_EQUAL p99 AND
       p99 LESS_EQUAL max)
get(published daemonTimesPublished)
expect("the daemon's per-frame times published" published)
get(withTimes whole framesWithDaemonTimes)
expect("daemon times for all ${FRAMES} frames, got ${withTimes}" withTimes EQUAL FRAMES)
get(march whole meanMs march)
expect("a mean march time >= 0, got ${march}" march GREATER_EQUAL 0)
get(publish whole meanMs publish)
expect("a mean publish time >= 0, got ${publish}" publish GREATER_EQUAL 0)
get(setup whole meanMs setup)
expect("a mean CPU setup time > 0 (the daemon's recent_frames setup_ms), got ${setup}" setup GREATER 0)

get(start slowestWindow startS)
expect("the slowest second starts within the path (0..${SECONDS} s), got ${start}" start GREATER_EQUAL 0 AND
       start LESS SECONDS)
get(windowFps slowestWindow fps)
expect("the slowest second's fps > 0 and <= the whole path's, got ${windowFps}" windowFps GREATER 0 AND
       windowFps LESS_EQUAL fps)
get(altitude slowestWindow pose altitudeM)
expect("the slowest second's altitude within 300..3900 m, got ${altitude}" altitude GREATER_EQUAL 300 AND
       altitude LESS_EQUAL 3900)
get(windowMarch slowestWindow meanMs march)
expect("the slowest second's mean march >= 0, got ${windowMarch}" windowMarch GREATER_EQUAL 0)

get(layer cloudLayers 0 layer)
expect("the eye inside the low layer, got ${layer}" layer STREQUAL "low")
get(enter cloudLayers 0 enterS)
get(leave cloudLayers 0 leaveS)
expect("inside the cumulus from about 60 s to 193 s, got ${enter}..${leave}" enter GREATER 50 AND enter LESS 75 AND
       leave GREATER 180 AND leave LESS 200)
message(STATUS "${JSON}: ${frames} frames along the flight path, consistent")
