# client_demo: the CPU compositing (display frame and depth compositing with the compositing layers)
# and shadow lookup as unit tests, and the demo end to end against the real daemon (headless capture over
# both transports, compositing by layers, and the window under Xvfb). The
# end-to-end tests skip (exit 77) until `skyservice` runs the daemon (it accepts --config).
if(TARGET client_demo_core)
    add_executable(client_demo_test ${CMAKE_CURRENT_LIST_DIR}/client_demo/compositing_test.cpp
                                    ${CMAKE_CURRENT_LIST_DIR}/client_demo/layer_compositing_test.cpp)
    target_link_libraries(client_demo_test PRIVATE client_demo_core GTest::gtest_main sky_warnings)
    gtest_discover_tests(client_demo_test TEST_PREFIX client_demo. PROPERTIES LABELS cpu)
endif()

if(TARGET client_demo AND TARGET skyservice)
    add_executable(client_demo_png_check ${CMAKE_CURRENT_LIST_DIR}/client_demo/png_check.cpp)
    target_link_libraries(client_demo_png_check PRIVATE client_demo_output sky_warnings)
    set(demo_script_dir ${CMAKE_CURRENT_LIST_DIR}/client_demo)
    foreach(transport shm vulkan)
        add_test(NAME client_demo.headless_capture_${transport}
                 COMMAND ${demo_script_dir}/headless_capture.sh $<TARGET_FILE:skyservice> $<TARGET_FILE:client_demo>
                         $<TARGET_FILE:client_demo_png_check> ${transport})
        set_tests_properties(client_demo.headless_capture_${transport} PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 240)
    endforeach()
    add_test(NAME client_demo.headless_layers
             COMMAND ${demo_script_dir}/headless_layers.sh $<TARGET_FILE:skyservice> $<TARGET_FILE:client_demo>
                     $<TARGET_FILE:client_demo_png_check>)
    set_tests_properties(client_demo.headless_layers PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 240)
    add_test(NAME client_demo.windowed_xvfb
             COMMAND ${demo_script_dir}/windowed_xvfb.sh $<TARGET_FILE:skyservice> $<TARGET_FILE:client_demo>
                     $<TARGET_FILE:client_demo_png_check>)
    set_tests_properties(client_demo.windowed_xvfb PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 240)
endif()

# The tiny libskyclient examples, one per transport, against the real daemon.
if(TARGET skyservice AND TARGET example-shm AND TARGET example-files AND TARGET client_demo_png_check)
    set(example_vulkan "")
    if(TARGET example-vulkan)
        set(example_vulkan $<TARGET_FILE:example-vulkan>)
    endif()
    add_test(NAME client_demo.examples
             COMMAND ${CMAKE_CURRENT_LIST_DIR}/client_demo/examples.sh $<TARGET_FILE:skyservice>
                     $<TARGET_FILE:client_demo_png_check> $<TARGET_FILE:example-shm> $<TARGET_FILE:example-files>
                     ${example_vulkan})
    set_tests_properties(client_demo.examples PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 240)
endif()
