# Temporal reprojection tests (issue 5, reprojection.*): phase order and history limits on the CPU;
# convergence, teleport and pan PSNR on the GPU with validation on.
add_executable(test_reprojection gpu/test_reprojection.cpp gpu/scenes.cpp)
target_link_libraries(test_reprojection PRIVATE sky_renderer GTest::gtest_main sky_warnings)
gtest_discover_tests(test_reprojection TEST_PREFIX "reprojection." DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300)
