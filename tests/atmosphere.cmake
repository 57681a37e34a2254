# Sun/moon ephemeris and the atmosphere model (ctest names atmo.*). CPU only: the shader math of
# shaders/lib/atmosphere*.glsl and phase.glsl is compiled as C++ (docs/style.md §8).
add_executable(test_atmosphere
    ${CMAKE_CURRENT_LIST_DIR}/unit/test_ephemeris.cpp
    ${CMAKE_CURRENT_LIST_DIR}/unit/test_atmosphere.cpp)
target_link_libraries(test_atmosphere PRIVATE sky_renderer GTest::gtest_main sky_warnings)
gtest_discover_tests(test_atmosphere TEST_PREFIX "atmo." DISCOVERY_TIMEOUT 60)
