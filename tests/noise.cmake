# Cloud noise (docs/model.md): shaders/lib/noise.glsl compiled as C++, and the CPU blue noise.
add_executable(test_noise unit/test_noise.cpp)
target_link_libraries(test_noise PRIVATE sky_renderer GTest::gtest_main sky_warnings)
gtest_discover_tests(test_noise TEST_PREFIX "noise." DISCOVERY_TIMEOUT 30)

# Not a test (tests never time things): prints the CPU cost of the noise textures' per-texel recipes.
add_executable(bench_noise unit/bench_noise.cpp)
target_link_libraries(bench_noise PRIVATE sky_renderer Threads::Threads sky_warnings)
