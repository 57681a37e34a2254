# libFuzzer targets of the daemon's readers of untrusted text (none may crash it): parseRequest and the config
# reader, built with clang by a separate project (skyservice/service/fuzz), then run a few seconds each.
set(SKY_SERVICE_FUZZ_DIR ${CMAKE_CURRENT_BINARY_DIR}/service-fuzz)
get_filename_component(SKY_SERVICE_FUZZ_ROOT ${CMAKE_CURRENT_LIST_DIR}/.. ABSOLUTE)
add_test(NAME service.fuzz.build
         COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/service/fuzz_test.sh build ${SKY_SERVICE_FUZZ_ROOT}
                 ${SKY_SERVICE_FUZZ_DIR})
set_tests_properties(service.fuzz.build PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 600 FIXTURES_SETUP service_fuzz
                     RUN_SERIAL ON)
foreach(target protocol service_config)
    add_test(NAME service.fuzz.${target}
             COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/service/fuzz_test.sh ${target} ${SKY_SERVICE_FUZZ_ROOT}
                     ${SKY_SERVICE_FUZZ_DIR} 8)
    set_tests_properties(service.fuzz.${target} PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 60
                         FIXTURES_REQUIRED service_fuzz)
endforeach()
