# Tests of skyservice/cigi/ (the CIGI 3.3 IG interface, CPU layer). Every test name starts with "cigi.".
set(SKY_CIGI_TEST_DIR ${CMAKE_CURRENT_LIST_DIR}/cigi)

if(TARGET sky_cigi)
    add_executable(test_cigi
        ${SKY_CIGI_TEST_DIR}/cigi_packets_test.cpp
        ${SKY_CIGI_TEST_DIR}/cigi_decoder_test.cpp
        ${SKY_CIGI_TEST_DIR}/cigi_state_test.cpp
        ${SKY_CIGI_TEST_DIR}/cigi_tshark_test.cpp
        ${SKY_CIGI_TEST_DIR}/geoid_test.cpp)
    target_include_directories(test_cigi PRIVATE ${SKY_CIGI_TEST_DIR})
    target_link_libraries(test_cigi PRIVATE sky_cigi GTest::gtest_main sky_warnings)
    gtest_discover_tests(test_cigi TEST_PREFIX "cigi." DISCOVERY_TIMEOUT 30 PROPERTIES LABELS cpu)
endif()

# libFuzzer: built with clang by a separate project (skyservice/cigi/fuzz), then run a few seconds on seeds.
set(SKY_CIGI_FUZZ_DIR ${CMAKE_CURRENT_BINARY_DIR}/cigi-fuzz)
get_filename_component(SKY_CIGI_ROOT ${CMAKE_CURRENT_LIST_DIR}/.. ABSOLUTE)
add_test(NAME cigi.fuzz.build
         COMMAND bash ${SKY_CIGI_TEST_DIR}/fuzz_test.sh build ${SKY_CIGI_ROOT} ${SKY_CIGI_FUZZ_DIR})
set_tests_properties(cigi.fuzz.build PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 600 FIXTURES_SETUP cigi_fuzz RUN_SERIAL ON)
add_test(NAME cigi.fuzz.decoder
         COMMAND bash ${SKY_CIGI_TEST_DIR}/fuzz_test.sh decoder ${SKY_CIGI_ROOT} ${SKY_CIGI_FUZZ_DIR} 8)
set_tests_properties(cigi.fuzz.decoder PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 60 FIXTURES_REQUIRED cigi_fuzz)

# The daemon's side (skyservice/service/cigi_*: eye, frustum, weather snapshot, conditions, applying a
# datagram to the next frame, the host's weather over a gridded one): CPU only, linked with the service
# library. The daemon end to end with a test host is in tests/service/test_service_cigi.cpp.
if(TARGET sky_cigi AND TARGET sky_service)
    add_executable(test_cigi_service ${SKY_CIGI_TEST_DIR}/cigi_service_test.cpp ${SKY_CIGI_TEST_DIR}/cigi_fade_test.cpp
                   ${SKY_CIGI_TEST_DIR}/cigi_merge_test.cpp)
    target_include_directories(test_cigi_service PRIVATE ${SKY_CIGI_TEST_DIR} ${PROJECT_SOURCE_DIR})
    target_link_libraries(test_cigi_service PRIVATE sky_service sky_cigi GTest::gtest_main sky_warnings)
    gtest_discover_tests(test_cigi_service TEST_PREFIX "cigi." DISCOVERY_TIMEOUT 30 PROPERTIES LABELS cpu)
endif()

# On the GPU (lavapipe): a fade of the host's weather, staged step by step through the weather schedule, keeps
# the renderer's reprojection history; a new snapshot drops it.
if(TARGET sky_cigi AND TARGET sky_service)
    add_executable(test_cigi_history ${SKY_CIGI_TEST_DIR}/cigi_history_gpu_test.cpp ${CMAKE_CURRENT_LIST_DIR}/gpu/scenes.cpp)
    target_include_directories(test_cigi_history PRIVATE ${SKY_CIGI_TEST_DIR} ${PROJECT_SOURCE_DIR})
    target_link_libraries(test_cigi_history PRIVATE sky_service sky_cigi GTest::gtest_main sky_warnings)
    gtest_discover_tests(test_cigi_history TEST_PREFIX "cigi." DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300)
endif()
