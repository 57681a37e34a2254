# Cloud shader math compiled as C++ (cloud.*), and SPIR-V reflection (vk.*): CPU only.
add_executable(test_cloud_math unit/test_cloud_math.cpp unit/test_reflection.cpp)
target_link_libraries(test_cloud_math PRIVATE sky_renderer GTest::gtest_main sky_warnings)
gtest_discover_tests(test_cloud_math TEST_PREFIX "cloud." DISCOVERY_TIMEOUT 30 PROPERTIES LABELS cpu)

# Frame uniforms (frame.*): clouds fixed to the earth, drifting only with the wind; off-centre frusta.
add_executable(test_frame_setup unit/test_frame_setup.cpp unit/test_view_frustum.cpp)
target_link_libraries(test_frame_setup PRIVATE sky_renderer GTest::gtest_main sky_warnings)
gtest_discover_tests(test_frame_setup TEST_PREFIX "frame." DISCOVERY_TIMEOUT 30 PROPERTIES LABELS cpu)
