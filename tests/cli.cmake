# Command-line tests of skyservice (cli.*): exit codes and messages (docs/style.md §14: good input passes, bad
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
# Without a subcommand skyservice is the daemon: a bad daemon option is refused with exit 2.
add_test(NAME cli.daemon.bad_log_level COMMAND ${SKY_EXPECT} 2 "log-level" ${SKY_BIN} --log-level loud)
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
# An off-centre frustum: the four half-angles together, never with --fov, left + right over 1 degree.
add_test(NAME cli.render.frustum_with_fov COMMAND ${SKY_EXPECT} 2 "excludes --(left|right|up|down|fov)"
         ${SKY_BIN} render --left 40 --right 0 --up 20 --down 20 --fov 30)
add_test(NAME cli.render.frustum_incomplete COMMAND ${SKY_EXPECT} 2 "--left requires --(right|up|down)"
         ${SKY_BIN} render --left 40)
add_test(NAME cli.render.frustum_too_narrow COMMAND ${SKY_EXPECT} 2 "left \\+ right" ${SKY_BIN} render
         --left 40 --right -39.5 --up 20 --down 20)
# A display wall's left channel renders, and its sidecar gives the four angles instead of fov.
add_test(NAME cli.render.frustum_channel COMMAND ${SKY_EXPECT} 0 "wrote .*channel\\.png" ${SKY_BIN} render
         --quality test --width 32 --height 18 --left 40 --right 0 --up 12 --down 12 --out ${SKY_CLI_TMP}/channel)
set_tests_properties(cli.render.frustum_channel PROPERTIES TIMEOUT 300)
add_test(NAME cli.render.frustum_sidecar COMMAND ${CMAKE_COMMAND} -E cat ${SKY_CLI_TMP}/channel.json)
set_tests_properties(cli.render.frustum_sidecar PROPERTIES DEPENDS cli.render.frustum_channel
                     PASS_REGULAR_EXPRESSION "\"left\": ?40\\.0.*\"right\": ?0\\.0"
                     FAIL_REGULAR_EXPRESSION "\"fov\"")
# A config file with an unknown key is refused and the key is named (exit 2).
file(WRITE ${SKY_CLI_TMP}/bad-key.toml "[march]\nmax_view_step = 10\n")
add_test(NAME cli.config.unknown_key COMMAND ${SKY_EXPECT} 2 "march.max_view_step" ${SKY_BIN} render
         --config ${SKY_CLI_TMP}/bad-key.toml)
# A key of an earlier version that became an experiment's knob (render_tuning.h) is refused, named, as removed.
file(WRITE ${SKY_CLI_TMP}/removed-key.toml "[lighting]\ncone_tail_reuse_m = 200.0\n")
add_test(NAME cli.config.removed_key COMMAND ${SKY_EXPECT} 2 "lighting.cone_tail_reuse_m' was removed"
         ${SKY_BIN} render --config ${SKY_CLI_TMP}/removed-key.toml)
# A value out of range is refused with the range.
file(WRITE ${SKY_CLI_TMP}/bad-range.toml "[lighting]\nphase_forward_g = 1.5\n")
add_test(NAME cli.config.out_of_range COMMAND ${SKY_EXPECT} 2 "phase_forward_g.*outside" ${SKY_BIN} render
         --config ${SKY_CLI_TMP}/bad-range.toml)
# A file that is not TOML is refused with line and column.
file(WRITE ${SKY_CLI_TMP}/not-toml.toml "[march\nthis is = = not toml\n")
add_test(NAME cli.config.syntax COMMAND ${SKY_EXPECT} 2 "not-toml.toml:[0-9]+:[0-9]+" ${SKY_BIN} render
         --config ${SKY_CLI_TMP}/not-toml.toml)
# Noise periods that do not divide the common modulus would make clouds jump: refused.
file(WRITE ${SKY_CLI_TMP}/bad-period.toml "[noise]\nbase_period_m = 7000.0\n")
add_test(NAME cli.config.noise_period COMMAND ${SKY_EXPECT} 2 "does not divide" ${SKY_BIN} render
         --config ${SKY_CLI_TMP}/bad-period.toml)
# The documented default file is valid and renders.
add_test(NAME cli.config.default_file COMMAND ${SKY_EXPECT} 0 "wrote" ${SKY_BIN} render --config
         ${PROJECT_SOURCE_DIR}/config/default.toml --quality test --accumulate 1 --steps 32 --width 32 --height 18
         --out ${SKY_CLI_TMP}/config-default)
set_tests_properties(cli.config.default_file PROPERTIES TIMEOUT 300)
# No Vulkan driver: a clear message and exit 1, never a crash.
add_test(NAME cli.render.no_vulkan_driver COMMAND ${CMAKE_COMMAND} -E env VK_DRIVER_FILES=/nonexistent/icd.json
         VK_ICD_FILENAMES=/nonexistent/icd.json ${SKY_EXPECT} 1 "Vulkan" ${SKY_BIN} render --quality test
         --width 16 --height 16 --out ${SKY_CLI_TMP}/never)
# A device index that does not exist is named.
add_test(NAME cli.render.no_such_device COMMAND ${SKY_EXPECT} 1 "--device 42" ${SKY_BIN} render --device 42
         --quality test --width 16 --height 16 --out ${SKY_CLI_TMP}/never)
# The CIGI options are range-checked like the others.
add_test(NAME cli.daemon.bad_cigi_port COMMAND ${SKY_EXPECT} 2 "--cigi-port" ${SKY_BIN} --cigi-port 70000)
