# Cloud shadow map tests (shadow.*): clear, overcast, cirrus and isolated-cell shadows on the
# GPU with validation on, the metadata against GeographicLib, and the command line's files.
add_executable(test_shadow gpu/test_shadow_map.cpp gpu/scenes.cpp)
target_link_libraries(test_shadow PRIVATE sky_renderer GTest::gtest_main sky_warnings)
target_compile_definitions(test_shadow PRIVATE SKY_SKYSERVICE_EXE="$<TARGET_FILE:skyservice>")
add_dependencies(test_shadow skyservice)
gtest_discover_tests(test_shadow TEST_PREFIX "shadow." DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 600)
