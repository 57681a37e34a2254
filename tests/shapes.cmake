# Cloud shape tests (shapes.*): no cloud below the layer base, no repetition in the shadow map.
add_executable(test_cloud_shapes gpu/test_cloud_shapes.cpp gpu/scenes.cpp)
target_link_libraries(test_cloud_shapes PRIVATE sky_renderer GTest::gtest_main sky_warnings)
gtest_discover_tests(test_cloud_shapes TEST_PREFIX "shapes." DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 600)
