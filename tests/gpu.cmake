# GPU tests (gpu.*): the renderer on the available Vulkan device (lavapipe in CI) with validation on.
add_executable(test_gpu gpu/test_render.cpp gpu/scenes.cpp)
target_link_libraries(test_gpu PRIVATE sky_renderer GTest::gtest_main sky_warnings)
gtest_discover_tests(test_gpu TEST_PREFIX "gpu." DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 900)
