# The launch order of the march's workgroup rows (shaders/shared/march_order.h): the CPU order functions
# (march_order.*, label cpu) and on the GPU (lavapipe, validation on) that the order changes no pixel,
# that the next frame launches the rows its predecessor measured costliest first, and what they count.
add_executable(test_march_order_cpu unit/test_march_order.cpp)
target_link_libraries(test_march_order_cpu PRIVATE sky_renderer GTest::gtest_main sky_warnings)
gtest_discover_tests(test_march_order_cpu TEST_PREFIX "march_order." DISCOVERY_TIMEOUT 30 PROPERTIES LABELS cpu)

add_executable(test_march_order gpu/test_march_order.cpp gpu/scenes.cpp)
target_link_libraries(test_march_order PRIVATE sky_renderer GTest::gtest_main sky_warnings)
gtest_discover_tests(test_march_order TEST_PREFIX "march_order." DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300)
