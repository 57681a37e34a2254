# Tests of skyservice/cigi/ (issue 21: CIGI 3.3 IG interface, CPU layer). Every test name starts with "cigi.".
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
