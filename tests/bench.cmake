# sky-bench command-line tests (bench.*): exit codes, messages and the shape of its output. Timings are
# never asserted here (lavapipe wall clock says nothing of a GPU's); BENCHMARKS.md holds GPU figures.
set(SKY_BENCH_EXPECT ${CMAKE_CURRENT_LIST_DIR}/cli/expect.sh)
set(SKY_BENCH_BIN $<TARGET_FILE:sky-bench>)
set(SKY_BENCH_TMP ${CMAKE_CURRENT_BINARY_DIR}/bench_tmp)
file(MAKE_DIRECTORY ${SKY_BENCH_TMP})

# Reprojected mode on a tiny clear sky with validation on, the eye flying at 250 m/s (--speed: a new
# eye position every frame): three frames through the temporal loop print a row with six median/p95 cells
# (sky, march, reconstruct, composite, total, wall) where full mode has five.
add_test(NAME bench.reprojected_small_validated COMMAND ${SKY_BENCH_EXPECT} 0
         "^clear( +[0-9.]+/[0-9.]+){6} +[0-9.]+ +0\\.0$"
         ${SKY_BENCH_BIN} --scene clear --width 32 --height 18 --frames 2 --warmup 1 --mode reprojected --validate
         --speed 250 --json ${SKY_BENCH_TMP}/reprojected.json)
set_tests_properties(bench.reprojected_small_validated PROPERTIES TIMEOUT 120)
add_test(NAME bench.reprojected_json COMMAND ${CMAKE_COMMAND} -E cat ${SKY_BENCH_TMP}/reprojected.json)
set_tests_properties(bench.reprojected_json PROPERTIES DEPENDS bench.reprojected_small_validated
                     PASS_REGULAR_EXPRESSION "\"eyeSpeedMps\": 250(\\.0)?,.*\"mode\": \"reprojected\".*\"march\".*\"reconstruct\"")
# Each scene reports the march's lookups per workgroup row (RenderResult::marchRowLookups).
add_test(NAME bench.reprojected_json_row_lookups COMMAND ${CMAKE_COMMAND} -E cat ${SKY_BENCH_TMP}/reprojected.json)
set_tests_properties(bench.reprojected_json_row_lookups PROPERTIES DEPENDS bench.reprojected_small_validated
                     PASS_REGULAR_EXPRESSION "\"marchRowLookups\": \\[\n? *[0-9]+")
# An unknown scene is a usage error that lists the known ones.
add_test(NAME bench.unknown_scene COMMAND ${SKY_BENCH_EXPECT} 2 "unknown scene \"fog\".*above-deck-FL350"
         ${SKY_BENCH_BIN} --scene fog)
# Modes other than full and reprojected are refused by the parser.
add_test(NAME bench.bad_mode COMMAND ${SKY_BENCH_EXPECT} 2 "mode" ${SKY_BENCH_BIN} --mode half)
# A tiny clear-sky run with validation on prints a row with four passes and the wall time (median/p95),
# the CPU setup time, and no cloud.
add_test(NAME bench.clear_small_validated COMMAND ${SKY_BENCH_EXPECT} 0
         "^clear( +[0-9.]+/[0-9.]+){5} +[0-9.]+ +0\\.0$"
         ${SKY_BENCH_BIN} --scene clear --width 32 --height 18 --frames 2 --warmup 1 --gpu-frames 2 --validate
         --json ${SKY_BENCH_TMP}/clear.json)
set_tests_properties(bench.clear_small_validated PROPERTIES TIMEOUT 120)
# The JSON names the device, the size and the per-pass medians.
add_test(NAME bench.clear_json COMMAND ${CMAKE_COMMAND} -E cat ${SKY_BENCH_TMP}/clear.json)
set_tests_properties(bench.clear_json PROPERTIES DEPENDS bench.clear_small_validated
                     PASS_REGULAR_EXPRESSION "\"gpuFramesPerCall\": 2.*\"height\": 18.*\"totalBytes\".*\"name\": \"clear\"")

# sky-service-bench: the real daemon and libskyclient clients on a tiny view. One synthetic scene
# (its weather goes through a snapshot file and load_weather), both transports, a few frames: the table's
# zero-copy row has its cells and no torn frame, and the JSON (checked by bench/check_service_json.cmake) counts every frame,
# delivers some per second, and orders its latencies. Timings themselves are never asserted.
if(TARGET sky-service-bench)
    set(SKY_SERVICE_BENCH_BIN $<TARGET_FILE:sky-service-bench>)
    add_test(NAME bench.service_small COMMAND ${SKY_BENCH_EXPECT} 0
             "^clear +160x90 +vulkan +[0-9.]+ +[0-9.]+/[0-9.]+/[0-9.]+ +[0-9.]+ +[0-9.]+ +0/0 "
             ${SKY_SERVICE_BENCH_BIN} --scene clear --size 160x90 --frames 4 --warmup 2 --transport both
             --json ${SKY_BENCH_TMP}/service.json)
    set_tests_properties(bench.service_small PROPERTIES TIMEOUT 180)
    add_test(NAME bench.service_json COMMAND ${CMAKE_COMMAND} -DJSON=${SKY_BENCH_TMP}/service.json -DFRAMES=4
             -DTRANSPORTS=shm,vulkan -P ${CMAKE_CURRENT_LIST_DIR}/bench/check_service_json.cmake)
    set_tests_properties(bench.service_json PROPERTIES DEPENDS bench.service_small)
    # The compositing layers reach the client (each subscribed layer is read; one missing fails the run).
    add_test(NAME bench.service_layers COMMAND ${SKY_BENCH_EXPECT} 0 "^clear +160x90 +shm "
             ${SKY_SERVICE_BENCH_BIN} --scene clear --size 160x90 --frames 3 --warmup 1 --transport shm
             --layers display,sky,clouds,depth)
    set_tests_properties(bench.service_layers PROPERTIES TIMEOUT 180)
    # The layers reach a Vulkan client too (exported images, each waited for and read).
    add_test(NAME bench.service_layers_vulkan COMMAND ${SKY_BENCH_EXPECT} 0 "^clear +160x90 +vulkan "
             ${SKY_SERVICE_BENCH_BIN} --scene clear --size 160x90 --frames 3 --warmup 1 --transport vulkan
             --layers display,clouds,depth)
    set_tests_properties(bench.service_layers_vulkan PROPERTIES TIMEOUT 180)
    # The flight path (--flight-path) in 30 coarse steps of 8 s over its four minutes: the report's table,
    # and its JSON (bench/check_flight_json.cmake) with the slowest second, the daemon's per-pass times
    # and the eye's stretch inside the cumulus layer.
    add_test(NAME bench.service_flight COMMAND ${SKY_BENCH_EXPECT} 0 "slowest second: from [0-9.]+ s"
             ${SKY_SERVICE_BENCH_BIN} --flight-path --size 32x18 --flight-step 8 --flight-seconds 240 --warmup 2
             --json ${SKY_BENCH_TMP}/flight.json)
    set_tests_properties(bench.service_flight PROPERTIES TIMEOUT 240)
    add_test(NAME bench.service_flight_json COMMAND ${CMAKE_COMMAND} -DJSON=${SKY_BENCH_TMP}/flight.json -DFRAMES=30
             -DSECONDS=240 -P ${CMAKE_CURRENT_LIST_DIR}/bench/check_flight_json.cmake)
    set_tests_properties(bench.service_flight_json PROPERTIES DEPENDS bench.service_flight)
    # A flight path through both transports at once is a usage error.
    add_test(NAME bench.service_flight_both COMMAND ${SKY_BENCH_EXPECT} 2 "--flight-path: one --size"
             ${SKY_SERVICE_BENCH_BIN} --flight-path --transport both)
    # A malformed size is a usage error that names the argument; no daemon starts.
    # (Not labelled cpu: ./sky test's sanitizer build does not build the bench.)
    add_test(NAME bench.service_bad_size COMMAND ${SKY_BENCH_EXPECT} 2 "--size 1920by1080: expected WIDTHxHEIGHT"
             ${SKY_SERVICE_BENCH_BIN} --size 1920by1080)
    # A daemon that cannot start: the message shows the end of its log ("  | " lines), which names the device.
    add_test(NAME bench.service_daemon_fails COMMAND ${SKY_BENCH_EXPECT} 1
             "^  \\| .*no-such-gpu: no such device"
             ${SKY_SERVICE_BENCH_BIN} --scene clear --size 16x16 --frames 1 --device no-such-gpu)
    set_tests_properties(bench.service_daemon_fails PROPERTIES TIMEOUT 120)
    add_test(NAME bench.service_bad_transport COMMAND ${SKY_BENCH_EXPECT} 2 "transport"
             ${SKY_SERVICE_BENCH_BIN} --transport pigeon)
endif()
