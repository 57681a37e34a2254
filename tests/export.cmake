# Zero-copy frame export tests (export.*): render, export through VK_KHR_external_memory_fd,
# pass the fds over a socketpair (SCM_RIGHTS) to an exec'd child that imports them with skyclient_vulkan
# into its own VkDevice, validation on in both processes; clean failure without the extension.
if(NOT TARGET skyclient_vulkan)  # normally added by skyservice/client/CMakeLists.txt
    add_subdirectory(${PROJECT_SOURCE_DIR}/skyservice/client/vulkan ${CMAKE_BINARY_DIR}/skyclient_vulkan_for_tests)
endif()
add_executable(test_export export/test_frame_export.cpp export/import_child.cpp gpu/scenes.cpp)
target_link_libraries(test_export PRIVATE sky_renderer skyclient_vulkan GTest::gtest sky_warnings)
gtest_discover_tests(test_export TEST_PREFIX "export." DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300)
