# Geodesy, weather window, built-in weather (geo.*) and file outputs (out.*): CPU only, no device.
add_executable(test_geo unit/test_geodesy.cpp unit/test_weather_window.cpp unit/test_builtin_weather.cpp)
target_link_libraries(test_geo PRIVATE sky_renderer GTest::gtest_main sky_warnings)
gtest_discover_tests(test_geo TEST_PREFIX "geo." DISCOVERY_TIMEOUT 30 PROPERTIES LABELS cpu)

add_executable(test_outputs unit/test_outputs.cpp)
target_link_libraries(test_outputs PRIVATE sky_renderer GTest::gtest_main sky_warnings)
gtest_discover_tests(test_outputs TEST_PREFIX "out." DISCOVERY_TIMEOUT 30 PROPERTIES LABELS cpu)

# The civil calendar and ISO 8601 times (weather_ingest/civil_time.h), used by the weather, CIGI, the service and
# the client library alike.
add_executable(test_civil_time unit/test_civil_time.cpp)
target_link_libraries(test_civil_time PRIVATE sky_weather GTest::gtest_main sky_warnings)
gtest_discover_tests(test_civil_time TEST_PREFIX "geo." DISCOVERY_TIMEOUT 30 PROPERTIES LABELS cpu)
