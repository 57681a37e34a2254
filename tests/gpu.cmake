# GPU tests (gpu.*): the renderer on the available Vulkan device (lavapipe in CI) with validation on.
add_executable(test_gpu gpu/test_render.cpp gpu/scenes.cpp gpu/image_compare.cpp)
target_link_libraries(test_gpu PRIVATE sky_renderer GTest::gtest_main sky_warnings)
gtest_discover_tests(test_gpu TEST_PREFIX "gpu." DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 900)

# The uniform- and storage-buffer shader variants draw the same frame (shaders/shared/bindings.h).
add_executable(test_param_blocks gpu/test_param_blocks.cpp gpu/scenes.cpp)
target_link_libraries(test_param_blocks PRIVATE sky_renderer GTest::gtest_main sky_warnings)
gtest_discover_tests(test_param_blocks TEST_PREFIX "gpu." DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300)

# Device memory (the budget: <= 64 MB at 1920x1080 in both render modes): the tracker's totals with and
# without the linear frame, the reprojection images after leaving a cloud, the budget at 1080p.
add_executable(test_memory gpu/test_memory.cpp gpu/scenes.cpp)
target_link_libraries(test_memory PRIVATE sky_renderer GTest::gtest_main sky_warnings)
gtest_discover_tests(test_memory TEST_PREFIX "gpu." DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 600)

add_executable(test_aerial_lut gpu/test_aerial_lut.cpp gpu/scenes.cpp)
target_link_libraries(test_aerial_lut PRIVATE sky_renderer GTest::gtest_main sky_warnings)
gtest_discover_tests(test_aerial_lut TEST_PREFIX "gpu." DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 600)

add_executable(test_light_volume gpu/test_light_volume.cpp gpu/test_cone_tail.cpp gpu/scenes.cpp gpu/image_compare.cpp)
target_link_libraries(test_light_volume PRIVATE sky_renderer GTest::gtest_main sky_warnings)
gtest_discover_tests(test_light_volume TEST_PREFIX "gpu." DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 600)

# The frame path: compositing layers, frames in flight, readback of only what was asked for.
add_executable(test_frame_path gpu/test_frame_path.cpp gpu/scenes.cpp)
target_link_libraries(test_frame_path PRIVATE sky_renderer GTest::gtest_main sky_warnings)
gtest_discover_tests(test_frame_path TEST_PREFIX "gpu." DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 600)
