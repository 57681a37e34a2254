# The sources of sky_weather (weather_ingest/CMakeLists.txt), relative to this folder: one list, so that
# the fuzz projects (weather_ingest/fuzz, skyservice/*/fuzz), built apart with clang, link what the main
# build links.
set(SKY_WEATHER_SOURCE_NAMES civil_time.cpp crc32c.cpp lat_lon_grid.cpp snapshot_blend.cpp snapshot_file.cpp
    weather_timeline.cpp)
set(SKY_WEATHER_SOURCES "")
foreach(s ${SKY_WEATHER_SOURCE_NAMES})
    list(APPEND SKY_WEATHER_SOURCES ${CMAKE_CURRENT_LIST_DIR}/${s})
endforeach()
