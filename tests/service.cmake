# End-to-end tests of the service: each starts the real `skyservice` daemon as a child process
# with a temporary config (tiny frames, quality "test", its own socket and shared-memory names) and
# drives it through libskyclient and raw sockets. service.soak.* is the short CI soak;
# tests/service/soak.sh runs a long one by hand.
if(TARGET sky_service AND TARGET skyclient)
    file(GLOB SKY_SERVICE_TEST_SOURCES CONFIGURE_DEPENDS ${CMAKE_CURRENT_LIST_DIR}/service/*.cpp)
    # test_service_vulkan_layers imports the exported layers with the export tests' importer.
    if(NOT TARGET skyclient_vulkan)
        add_subdirectory(${PROJECT_SOURCE_DIR}/skyservice/client/vulkan
                         ${CMAKE_BINARY_DIR}/skyclient_vulkan_for_service_tests)
    endif()
    add_executable(service_e2e_test ${SKY_SERVICE_TEST_SOURCES} ${CMAKE_CURRENT_LIST_DIR}/export/import_child.cpp)
    target_include_directories(service_e2e_test PRIVATE ${PROJECT_SOURCE_DIR})
    target_compile_definitions(service_e2e_test PRIVATE SKY_SERVICE_BIN="$<TARGET_FILE:skyservice>")
    target_compile_definitions(service_e2e_test PRIVATE SKY_PROJECT_DIR="${PROJECT_SOURCE_DIR}")
    target_link_libraries(service_e2e_test PRIVATE skyclient skyclient_vulkan sky_service sky_renderer sky_weather
                                                   GTest::gtest_main sky_warnings)
    add_dependencies(service_e2e_test skyservice)
    gtest_discover_tests(service_e2e_test TEST_PREFIX service. PROPERTIES TIMEOUT 240)
endif()

# The daemon's parts on the CPU, without a daemon: the log limiter.
if(TARGET sky_service)
    add_executable(test_service_cpu ${CMAKE_CURRENT_LIST_DIR}/service/unit/log_limiter_test.cpp)
    target_include_directories(test_service_cpu PRIVATE ${PROJECT_SOURCE_DIR})
    target_link_libraries(test_service_cpu PRIVATE sky_service GTest::gtest_main sky_warnings)
    gtest_discover_tests(test_service_cpu TEST_PREFIX "service.cpu." DISCOVERY_TIMEOUT 30 PROPERTIES LABELS cpu)
endif()
