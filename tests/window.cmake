# The weather window for a moving eye: the lattice of window centres on the CPU (window.*,
# label cpu), and on the GPU (lavapipe, validation on) that crossing a cell edge moves no cloud and that
# a flight makes its windows on the worker thread, not on the frame path. A new weather staged off the
# frame path and the speed-dependent look-ahead: their CPU logic (window.WeatherStage.*,
# window.WindowLookAhead.*, label cpu) and on the GPU (window.WeatherSwap.*).
add_executable(test_window_lattice unit/test_window_lattice.cpp)
target_link_libraries(test_window_lattice PRIVATE sky_renderer GTest::gtest_main sky_warnings)
gtest_discover_tests(test_window_lattice TEST_PREFIX "window." DISCOVERY_TIMEOUT 30 PROPERTIES LABELS cpu)

add_executable(test_window_motion gpu/test_window_motion.cpp gpu/scenes.cpp)
target_link_libraries(test_window_motion PRIVATE sky_renderer GTest::gtest_main sky_warnings)
gtest_discover_tests(test_window_motion TEST_PREFIX "window." DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300)

add_executable(test_weather_stage unit/test_weather_stage.cpp unit/test_weather_worker.cpp)
target_link_libraries(test_weather_stage PRIVATE sky_renderer GTest::gtest_main sky_warnings)
gtest_discover_tests(test_weather_stage TEST_PREFIX "window." DISCOVERY_TIMEOUT 30 PROPERTIES LABELS cpu TIMEOUT 300)

add_executable(test_weather_swap gpu/test_weather_swap.cpp gpu/scenes.cpp)
target_link_libraries(test_weather_swap PRIVATE sky_renderer GTest::gtest_main sky_warnings)
gtest_discover_tests(test_weather_swap TEST_PREFIX "window." DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300)

# The weather window's column-bounds pyramid for the march's empty-space skipping (CPU).
add_executable(test_column_bounds unit/test_column_bounds.cpp)
target_link_libraries(test_column_bounds PRIVATE sky_renderer GTest::gtest_main sky_warnings)
gtest_discover_tests(test_column_bounds TEST_PREFIX "window." DISCOVERY_TIMEOUT 30 PROPERTIES LABELS cpu)
