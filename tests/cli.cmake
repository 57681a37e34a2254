# Command-line tests of skyservice (cli.*): exit codes and messages (STYLE §16: good input passes, bad
# input fails with a message naming what was wrong). Each comment names what it guards.
set(SKY_EXPECT ${CMAKE_CURRENT_LIST_DIR}/cli/expect.sh)
set(SKY_BIN $<TARGET_FILE:skyservice>)
set(SKY_CLI_TMP ${CMAKE_CURRENT_BINARY_DIR}/cli_tmp)
file(MAKE_DIRECTORY ${SKY_CLI_TMP})
file(WRITE ${SKY_CLI_TMP}/not-a-snapshot.skywx "this is not a weather snapshot\n")

# A latitude outside [-90, 90] is a usage error naming the option.
add_test(NAME cli.render.bad_latitude COMMAND ${SKY_EXPECT} 2 "--lat" ${SKY_BIN} render --lat 100)
# A malformed time is refused before any GPU work.
add_test(NAME cli.render.bad_time COMMAND ${SKY_EXPECT} 2 "--time" ${SKY_BIN} render --time 2026-13-45T00:00:00Z)
# A time without a zone is ambiguous.
add_test(NAME cli.render.time_without_zone COMMAND ${SKY_EXPECT} 2 "--time" ${SKY_BIN} render --time 2026-06-21T12:00:00)
# Image sizes are bounded.
add_test(NAME cli.render.bad_size COMMAND ${SKY_EXPECT} 2 "--width" ${SKY_BIN} render --width 0)
# Unknown options are usage errors.
add_test(NAME cli.render.unknown_option COMMAND ${SKY_EXPECT} 2 "junk" ${SKY_BIN} render --junk)
# A missing subcommand is a usage error.
add_test(NAME cli.no_subcommand COMMAND ${SKY_EXPECT} 2 "subcommand" ${SKY_BIN})
# A missing weather file is named in the error (exit 3), before the GPU starts.
add_test(NAME cli.render.missing_weather COMMAND ${SKY_EXPECT} 3 "no-such-file.skywx" ${SKY_BIN} render
         --weather ${SKY_CLI_TMP}/no-such-file.skywx --out ${SKY_CLI_TMP}/never)
# A file that is not a snapshot is refused with exit 3.
add_test(NAME cli.render.foreign_weather COMMAND ${SKY_EXPECT} 3 "not-a-snapshot" ${SKY_BIN} render
         --weather ${SKY_CLI_TMP}/not-a-snapshot.skywx --out ${SKY_CLI_TMP}/never)
# A small render with validation on writes the three files and reports them.
add_test(NAME cli.render.small_validated COMMAND ${SKY_EXPECT} 0 "wrote .*small\\.png" ${SKY_BIN} render
         --quality test --width 48 --height 27 --validate --out ${SKY_CLI_TMP}/small)
set_tests_properties(cli.render.small_validated PROPERTIES TIMEOUT 300)
add_test(NAME cli.render.small_files_exist COMMAND ${CMAKE_COMMAND} -E cat ${SKY_CLI_TMP}/small.json)
set_tests_properties(cli.render.small_files_exist PROPERTIES DEPENDS cli.render.small_validated
                     PASS_REGULAR_EXPRESSION "\"sun\"")
