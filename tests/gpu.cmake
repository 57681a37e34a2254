# GPU tests (gpu.*): the renderer on the available Vulkan device (lavapipe in CI) with validation on.
add_executable(test_gpu gpu/test_render.cpp gpu/scenes.cpp)
target_link_libraries(test_gpu PRIVATE sky_renderer GTest::gtest_main sky_warnings)
gtest_discover_tests(test_gpu TEST_PREFIX "gpu." DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 900)

# The uniform- and storage-buffer shader variants draw the same frame (shaders/shared/bindings.h).
add_executable(test_param_blocks gpu/test_param_blocks.cpp gpu/scenes.cpp)
target_link_libraries(test_param_blocks PRIVATE sky_renderer GTest::gtest_main sky_warnings)
gtest_discover_tests(test_param_blocks TEST_PREFIX "gpu." DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300)
