# Geo-referencing tests (georef.*): an isolated cell lands in the direction GeographicLib
# gives (mid-latitude, 78 N, across the antimeridian); the real GFS sample renders its low deck and its
# clear sky. GPU tests, validation on.
add_executable(test_georef gpu/test_georef.cpp gpu/scenes.cpp)
target_link_libraries(test_georef PRIVATE sky_renderer GTest::gtest_main sky_warnings)
if(TARGET sky_ingest)
    target_link_libraries(test_georef PRIVATE sky_ingest)
    target_compile_definitions(test_georef PRIVATE SKY_HAVE_INGEST SKY_SHARED_DIR="${SKY_SHARED_DIR}")
endif()
gtest_discover_tests(test_georef TEST_PREFIX "georef." DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 900)

# Geo-referencing on every grid type ecCodes can locate (grid_georef.*): a cloud cell written with ecCodes on a
# Lambert (one and two parallels), polar stereographic (north, south), Mercator, rotated, reduced Gaussian
# and reduced lat/lon grid, converted by sky_ingest, lands within 1 degree of its direction from 50 km.
if(TARGET sky_ingest)
    add_executable(test_grid_georef gpu/test_grid_georef.cpp gpu/scenes.cpp)
    target_link_libraries(test_grid_georef PRIVATE sky_renderer sky_ingest GTest::gtest_main sky_warnings)
    # One process for the eight grids: each ctest process would build its own renderer (noise and
    # atmosphere tables, ~3 s on lavapipe), more than a grid's conversion and picture take.
    add_test(NAME grid_georef.CellAppearsInItsGeodesicDirection COMMAND test_grid_georef)
    set_tests_properties(grid_georef.CellAppearsInItsGeodesicDirection PROPERTIES TIMEOUT 300)
endif()
