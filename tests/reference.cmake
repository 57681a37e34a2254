# The reference path tracer (reference.*): its sampling compiled as C++ (CPU), and on the GPU the
# plane-parallel slab against the published transfer, energy conservation, the built-in clouds.
add_executable(test_reference_sampling unit/test_phase_sampling.cpp)
target_link_libraries(test_reference_sampling PRIVATE sky_renderer GTest::gtest_main sky_warnings)
gtest_discover_tests(test_reference_sampling TEST_PREFIX "reference." DISCOVERY_TIMEOUT 30 PROPERTIES LABELS cpu)

add_executable(test_reference gpu/test_reference.cpp gpu/scenes.cpp)
target_link_libraries(test_reference PRIVATE sky_renderer GTest::gtest_main sky_warnings)
gtest_discover_tests(test_reference TEST_PREFIX "reference." DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300)

# sky-reference-looks (not a test: minutes on lavapipe): the issue's look views in real time and path
# traced, side by side in OUT/reference-looks.png, with their cloud luminance statistics.
add_executable(sky-reference-looks gpu/reference_looks.cpp gpu/look_stats.cpp gpu/scenes.cpp)
target_link_libraries(sky-reference-looks PRIVATE sky_app sky_renderer sky_warnings)

# The command line (reference.cli.*): a small path-traced render with validation on writes its files and
# says it path-traced; a phase function other than model or mie is a usage error naming the option.
add_test(NAME reference.cli.small_validated COMMAND ${CMAKE_CURRENT_LIST_DIR}/cli/expect.sh 0
         "wrote .*reference-small\\.png.*path tracing" $<TARGET_FILE:skyservice> render --quality test --width 16
         --height 9 --reference --spp 1 --phase mie --validate --out ${CMAKE_CURRENT_BINARY_DIR}/reference-small)
add_test(NAME reference.cli.bad_phase COMMAND ${CMAKE_CURRENT_LIST_DIR}/cli/expect.sh 2 "--phase"
         $<TARGET_FILE:skyservice> render --reference --phase rayleigh)

# The real-time lighting against the reference on the look views (app/look_views.h, reference.ReferenceLooks.*): the
# mean cloud luminance and the underside/top ratio, the reference rendered in the test at 48x27 and few samples;
# the view from above finishes with bounded work, and the dispatch bound ends a render that has not.
add_executable(test_reference_looks gpu/test_reference_looks.cpp gpu/look_stats.cpp gpu/scenes.cpp)
target_link_libraries(test_reference_looks PRIVATE sky_app sky_renderer GTest::gtest_main sky_warnings)
gtest_discover_tests(test_reference_looks TEST_PREFIX "reference." DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300)
