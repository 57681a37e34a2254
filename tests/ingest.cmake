# Tests of weather_ingest/. Every test name starts with "ingest.".
set(SKY_INGEST_TEST_DIR ${CMAKE_CURRENT_LIST_DIR}/ingest)

add_executable(ingest_weather_tests ${SKY_INGEST_TEST_DIR}/snapshot_file_test.cpp
               ${SKY_INGEST_TEST_DIR}/weather_timeline_test.cpp
               ${SKY_INGEST_TEST_DIR}/snapshot_hostile_test.cpp
               ${SKY_INGEST_TEST_DIR}/lat_lon_grid_test.cpp)
target_link_libraries(ingest_weather_tests PRIVATE sky_weather nlohmann_json::nlohmann_json GTest::gtest_main
                      sky_warnings)
gtest_discover_tests(ingest_weather_tests TEST_PREFIX "ingest." DISCOVERY_TIMEOUT 30 PROPERTIES LABELS cpu)

if(TARGET sky_ingest)
    add_executable(ingest_decoder_tests
        ${SKY_INGEST_TEST_DIR}/grib_ingest_test.cpp
        ${SKY_INGEST_TEST_DIR}/bad_input_test.cpp
        ${SKY_INGEST_TEST_DIR}/grid_types_test.cpp
        ${SKY_INGEST_TEST_DIR}/level_stack_test.cpp
        ${SKY_INGEST_TEST_DIR}/wrf_ingest_test.cpp)
    target_link_libraries(ingest_decoder_tests PRIVATE sky_ingest sky_netcdf GTest::gtest_main sky_warnings)
    target_compile_definitions(ingest_decoder_tests PRIVATE SKY_SHARED_DIR="${SKY_SHARED_DIR}")
    gtest_discover_tests(ingest_decoder_tests TEST_PREFIX "ingest." DISCOVERY_TIMEOUT 30)
endif()

if(TARGET sky-ingest)
    foreach(case info-gfs info-wrf convert-gfs convert-wrf empty png truncated netcdf-unrelated missing usage check-bad)
        add_test(NAME ingest.cli.${case}
                 COMMAND bash ${SKY_INGEST_TEST_DIR}/cli_test.sh ${case} $<TARGET_FILE:sky-ingest> ${SKY_SHARED_DIR}
                         ${CMAKE_CURRENT_BINARY_DIR}/ingest-cli)
        set_tests_properties(ingest.cli.${case} PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 60)
    endforeach()
endif()

# libFuzzer: built with clang by a separate project, then each target runs a few seconds on seeds.
if(SKY_BUILD_INGEST)
    set(SKY_INGEST_FUZZ_DIR ${CMAKE_CURRENT_BINARY_DIR}/ingest-fuzz)
    get_filename_component(SKY_INGEST_ROOT ${CMAKE_CURRENT_LIST_DIR}/.. ABSOLUTE)
    add_test(NAME ingest.fuzz.build
             COMMAND bash ${SKY_INGEST_TEST_DIR}/fuzz_test.sh build ${SKY_INGEST_ROOT} ${SKY_INGEST_FUZZ_DIR})
    set_tests_properties(ingest.fuzz.build PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 600 FIXTURES_SETUP ingest_fuzz
                         RUN_SERIAL ON)
    foreach(target grib snapshot snapshot_crafted)
        add_test(NAME ingest.fuzz.${target}
                 COMMAND bash ${SKY_INGEST_TEST_DIR}/fuzz_test.sh ${target} ${SKY_INGEST_ROOT} ${SKY_INGEST_FUZZ_DIR} 8)
        set_tests_properties(ingest.fuzz.${target} PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 60
                             FIXTURES_REQUIRED ingest_fuzz)
    endforeach()
endif()
