# Temporal reprojection tests (reprojection.*): phase order, history limits and march block on
# the CPU; convergence, teleport, weather swap, time jump and pan PSNR on the GPU with validation on.
add_library(sky_reprojection_test_support STATIC gpu/scenes.cpp gpu/image_compare.cpp gpu/sharpness.cpp)
target_link_libraries(sky_reprojection_test_support PUBLIC sky_renderer GTest::gtest sky_warnings)

add_executable(test_reprojection gpu/test_reprojection.cpp)
target_link_libraries(test_reprojection PRIVATE sky_reprojection_test_support GTest::gtest_main sky_warnings)
gtest_discover_tests(test_reprojection TEST_PREFIX "reprojection." DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300)

# World-space march jitter (shaders/lib/world_jitter.glsl; its CPU test is in unit/test_cloud_math.cpp):
# the same rays in another screen order, and a sub-pixel turn, on the GPU.
add_executable(test_world_jitter gpu/test_world_jitter.cpp)
target_link_libraries(test_world_jitter PRIVATE sky_reprojection_test_support GTest::gtest_main sky_warnings)
gtest_discover_tests(test_world_jitter TEST_PREFIX "reprojection." DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300)

# Scripted flight-path gates: cruise, 60 and 90 deg/s turns, climb through a deck.
add_executable(test_flight_path gpu/test_flight_path.cpp gpu/flight_path.cpp)
target_link_libraries(test_flight_path PRIVATE sky_reprojection_test_support GTest::gtest_main sky_warnings)
gtest_discover_tests(test_flight_path TEST_PREFIX "reprojection." DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300)

# Multi-channel: adjacent frusta agree at the shared edge; same inputs give the same bytes.
add_executable(test_channels gpu/test_channels.cpp gpu/flight_path.cpp)
target_link_libraries(test_channels PRIVATE sky_reprojection_test_support GTest::gtest_main sky_warnings)
gtest_discover_tests(test_channels TEST_PREFIX "reprojection." DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300)
