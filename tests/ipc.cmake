# CPU-side tests of the service's inter-process layer: the shared-memory frame ring, the
# control socket server, protocol validation, and libskyclient against an in-test fake service (no
# renderer, no Vulkan). Labelled "cpu": `./sky test` runs them again under ASan + UBSan.
if(TARGET sky_ipc AND TARGET skyclient)
    file(GLOB SKY_IPC_TEST_SOURCES CONFIGURE_DEPENDS ${CMAKE_CURRENT_LIST_DIR}/ipc/*.cpp ${CMAKE_CURRENT_LIST_DIR}/ipc/*.c)
    add_executable(ipc_test ${SKY_IPC_TEST_SOURCES})
    target_include_directories(ipc_test PRIVATE ${PROJECT_SOURCE_DIR})
    target_link_libraries(ipc_test PRIVATE sky_ipc skyclient GTest::gtest_main sky_warnings)
    gtest_discover_tests(ipc_test TEST_PREFIX ipc. PROPERTIES LABELS cpu TIMEOUT 60)
endif()
