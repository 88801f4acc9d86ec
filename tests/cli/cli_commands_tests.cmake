# Tests of the obscura CLI's commands (render, compare, bench, demo, truth, tune, the lists) and of its
# bad-argument handling, each a `cmake -P cli_commands_check.cmake` run: exit status, files written, and the
# JSON reports read back with string(JSON). Included from tests/CMakeLists.txt (after OBSCURA_GL_TEST_ENV is
# set). The GL ones render tiny images (analytic scene at 160x90, a 16-ray reference): about 0.5 s each
# on llvmpipe. tests/cli/CMakeLists.txt holds the `obscura diff` tests.
if(NOT TARGET obscura_cli)
  message(STATUS "obscura tests: the CLI is not built (OBSCURA_BUILD_SAMPLES=OFF); no CLI command tests")
  return()
endif()

set(OBSCURA_CLI_COMMANDS_DIR "${CMAKE_CURRENT_LIST_DIR}")
set(OBSCURA_CLI_COMMANDS_GPU OFF)
if(OBSCURA_TESTS_ON_GPU)
  set(OBSCURA_CLI_COMMANDS_GPU ON)
endif()

# obscura_cli_command_test(NAME EXPECT_EXIT ARGS [GL] [CHECK name] [EXPECT_STDOUT regex] [EXPECT_STDERR regex]
#                          [EXPECT_FILES f|g])
# ARGS: the command line after `obscura`, items separated by '|'. GL: the command creates a GL context
# (llvmpipe environment, label gl).
function(obscura_cli_command_test name expect_exit arguments)
  cmake_parse_arguments(PARSE_ARGV 3 TEST "GL" "CHECK;EXPECT_STDOUT;EXPECT_STDERR;EXPECT_FILES" "")
  set(options -DPROGRAM=$<TARGET_FILE:obscura_cli> "-DARGS=${arguments}" -DEXPECT_EXIT=${expect_exit}
              "-DWORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/cli_commands/${name}" -DGPU=${OBSCURA_CLI_COMMANDS_GPU})
  foreach(option CHECK EXPECT_STDOUT EXPECT_STDERR EXPECT_FILES)
    if(DEFINED TEST_${option})
      list(APPEND options "-D${option}=${TEST_${option}}")
    endif()
  endforeach()
  add_test(NAME obscura_cli.${name}
           COMMAND ${CMAKE_COMMAND} ${options} -P "${OBSCURA_CLI_COMMANDS_DIR}/cli_commands_check.cmake")
  if(TEST_GL)
    # demo renders every method at 640x360 (FFAO alone takes about 5 s a frame on llvmpipe with 2 cores).
    set(timeout 120)
    if(name STREQUAL "demo")
      set(timeout 300)
    endif()
    set_tests_properties(obscura_cli.${name} PROPERTIES TIMEOUT ${timeout} LABELS "gl;cli")
    if(OBSCURA_GL_TEST_ENV)
      set_tests_properties(obscura_cli.${name} PROPERTIES ENVIRONMENT "${OBSCURA_GL_TEST_ENV}")
    endif()
  else()
    set_tests_properties(obscura_cli.${name} PROPERTIES TIMEOUT 60 LABELS "unit;cli")
    if(OBSCURA_SANITIZER_TEST_ENV)
      set_tests_properties(obscura_cli.${name} PROPERTIES ENVIRONMENT "${OBSCURA_SANITIZER_TEST_ENV}")
    endif()
  endif()
endfunction()

set(scene "--scene|analytic|--size|160x90")

# ---- Commands (GL) ---------------------------------------------------------------------------------
obscura_cli_command_test(render_json 0
  "render|${scene}|--method|hbao:directions=4:steps=6|--out|ao.png|--pfm|ao.pfm|--json|render.json"
  GL CHECK render EXPECT_FILES "ao.png|ao.pfm" EXPECT_STDOUT "GL: [^\n]*\nscene: analytic")
obscura_cli_command_test(render_depth_file 0
  "render|--depth|${OBSCURA_CLI_COMMANDS_DIR}/data/plane_64x36_linear.pfm|--depth-kind|linear|--fovy|60|--method|hbao:directions=4:steps=6|--out|ao.png|--json|render.json"
  GL CHECK depth EXPECT_FILES "ao.png")
obscura_cli_command_test(compare_analytic 0
  "compare|${scene}|--methods|hbao,hbao:blur=off|--truth|both|--truth-rays|64|--reference-rays|16|--out-dir|out|--json|report.json"
  GL CHECK compare
  EXPECT_FILES "out/1_hbao.png|out/1_hbao_error_geometry.png|out/1_hbao_signed_geometry.png|out/1_hbao_signed_screen.png|out/1_hbao_error_screen.png|out/2_hbao.png|out/2_hbao_error_geometry.png|out/geometry_truth_1.png|out/reference_1.png|out/contact_sheet.png"
  EXPECT_STDOUT "errors against the geometry truth [(]64 rays[)] over [0-9]+ geometry pixels[^\n]*sky [0-9.]+ %[^\n]*\nmethod +gpu ms +wall ms +mean_abs +within_5pct +psnr dB +max_abs +signed[^\n]*\n.*errors against the screen-space reference [(]16 rays[)]")
# Metrics over every pixel: the sky counts (as zero error), so the same method scores better.
obscura_cli_command_test(compare_metrics_all_pixels 0
  "compare|${scene}|--methods|hbao|--truth-rays|16|--metrics-pixels|all|--out-dir|out"
  GL EXPECT_STDOUT "over every pixel of the 160x90")
# --strip: three methods, two of them sharing a reference (radius 1), so 3 + 2 labelled tiles in 2 rows of 3.
obscura_cli_command_test(compare_strip 0
  "compare|${scene}|--methods|hbao:radius=0.5,hbao:radius=1,hbao:blur=off|--truth-rays|16|--strip|strip.png"
  GL CHECK strip EXPECT_FILES "strip.png" EXPECT_STDOUT "wrote strip.png")
obscura_cli_command_test(compare_orbit_flicker 0
  "compare|${scene}|--methods|hbao|--truth-rays|64|--orbit|4|--frames|2|--json|report.json"
  GL CHECK orbit EXPECT_FILES "compare-output/1_hbao.png|compare-output/contact_sheet.png" EXPECT_STDOUT "flicker")
# --temporal on: the frames accumulate (the cameras and frame index reach the SDK), a spec's own key wins (the second
# method stays off), and the accumulated frames flicker less; the table and the report add the last frame's error
# (check orbit_temporal).
obscura_cli_command_test(compare_orbit_temporal 0
  "compare|${scene}|--methods|hbao,hbao:temporal.enabled=off|--temporal|on|--truth-rays|64|--orbit|4|--frames|3|--json|report.json"
  GL CHECK orbit_temporal EXPECT_STDOUT "flicker +last")
obscura_cli_command_test(compare_temporal_bad_value 2 "compare|--temporal|maybe" EXPECT_STDERR "--temporal takes on or off")
# The animated scene through a still camera: motion vectors handed over, each frame's converged image (--converged),
# the noise flicker against it, and the ghosting table with both curves.
obscura_cli_command_test(compare_sliding_ghosting 0
  "compare|--scene|sliding|--size|96x54|--methods|hbao:temporal.enabled=on|--truth-rays|8|--frames|3|--converged|2|--json|report.json"
  GL EXPECT_FILES "report.json"
  EXPECT_STDOUT "3 frames of a still camera, the scene moving, motion vectors handed over\n.*noise flicker +converged.*\nghosting [^\n]*\nmethod +pixels +within 0.02 from +0 +1[^\n]*\nhbao:temporal.enabled=on uncovered +[0-9]+ [^\n]*\nhbao:temporal.enabled=on changed ")
# An orbit with --converged: the ghosting table of the pixels whose surface came into view (samples::
# frames_since_disocclusion), its one curve; the sliding scene orbited too (its moving part followed back).
obscura_cli_command_test(compare_orbit_ghosting 0
  "compare|${scene}|--orbit|4|--frames|3|--converged|2|--truth-rays|4|--methods|hbao:temporal.enabled=on"
  GL EXPECT_STDOUT "ghosting [(]the moving camera[)][^\n]*\nmethod +pixels +within 0.02 from +0 +1[^\n]*\nhbao:temporal.enabled=on disoccluded +[1-9][0-9]* ")
obscura_cli_command_test(compare_sliding_orbit_ghosting 0
  "compare|--scene|sliding|--size|96x54|--orbit|4|--frames|3|--converged|2|--truth-rays|4|--methods|hbao:temporal.enabled=on"
  GL EXPECT_STDOUT "ghosting [(]the moving camera[)][^\n]*\nmethod +pixels +within 0.02 from +0 +1[^\n]*\nhbao:temporal.enabled=on disoccluded +[1-9][0-9]* ")
obscura_cli_command_test(compare_converged_without_frames 2 "compare|--converged|4" EXPECT_STDERR "--converged needs --frames N")
obscura_cli_command_test(compare_motion_vectors_bad_value 2 "compare|--motion-vectors|yes" EXPECT_STDERR "--motion-vectors takes on or off")
# bench --motion: the temporal pass's moving path is timed and reported.
obscura_cli_command_test(bench_temporal_motion 0
  "bench|--scene|analytic|--sizes|96x54|--methods|hbao:temporal.enabled=on|--motion|1|--frames|2|--warmup|1"
  GL EXPECT_STDOUT "\n  temporal +[0-9.]+")
# --classes: the geometry pixels split into silhouette, halo and rest, a line of counts and a table of each method's
# error per class, classes.png and the report's "classes" (check classes). Bare --classes (the defaults) before
# another option; a depth file's classes come from its depth.
obscura_cli_command_test(compare_classes 0
  "compare|${scene}|--methods|hbao,hbao:blur=off|--truth-rays|16|--classes|1,0.3|--out-dir|out|--json|report.json"
  GL CHECK classes EXPECT_FILES "out/classes.png|out/contact_sheet.png"
  EXPECT_STDOUT "\nclasses [(]radius 1 m, thickness 0.3 m, window <= 256 px[)]: silhouette [0-9]+ px [(][0-9.]+ %[)], halo [0-9]+ px [(][0-9.]+ %[)], rest [0-9]+ px [(][0-9.]+ %[)] of [0-9]+ geometry pixels\nmethod +silhouette: mean_abs +signed +halo: mean_abs +signed +rest: mean_abs +signed\nhbao +[0-9.]+ +[-+][0-9.]+ +[0-9.]+ +[-+][0-9.]+ +[0-9.]+ +[-+][0-9.]+\nhbao:blur=off ")
obscura_cli_command_test(compare_classes_defaults 0
  "compare|${scene}|--methods|hbao|--truth-rays|4|--classes|--out-dir|out"
  GL EXPECT_FILES "out/classes.png" EXPECT_STDOUT "classes [(]radius 1 m, thickness 0.3 m, ")
obscura_cli_command_test(compare_classes_depth_file 0
  "compare|--depth|${OBSCURA_CLI_COMMANDS_DIR}/data/plane_64x36_linear.pfm|--methods|hbao|--reference-rays|4|--classes|0.5"
  GL EXPECT_FILES "compare-output/classes.png" EXPECT_STDOUT "classes [(]radius 0.5 m, thickness 0.3 m, [^\n]* of 2304 geometry pixels\n")
obscura_cli_command_test(bench_two_sizes 0
  "bench|--scene|analytic|--sizes|160x90,96x54|--methods|hbao|--frames|2|--warmup|1|--json|bench.json|--csv|bench.csv"
  GL CHECK bench EXPECT_FILES "bench.csv" EXPECT_STDOUT "clock: ")
obscura_cli_command_test(bench_refused_configuration 1
  "bench|--scene|analytic|--sizes|2560x1440|--methods|ffao:sectors=64:base_interval=2,hbao:directions=4:steps=4|--frames|1|--warmup|0|--json|bench.json|--csv|bench.csv"
  GL CHECK bench_refused EXPECT_FILES "bench.csv")
# A size that cannot be rasterised fails its configurations, not the run: the others' results and the files are kept
# (a depth file that cannot be read stands in for it here). Until 2026-12-06 it lost every result, wrote no file.
obscura_cli_command_test(bench_scene_that_fails 1
  "bench|--depth|no_such_depth.pfm|--methods|hbao,hbao:blur=off|--frames|1|--warmup|0|--json|bench.json|--csv|bench.csv"
  GL EXPECT_FILES "bench.json|bench.csv" EXPECT_STDOUT "hbao:blur=off @ 0x0, clock [a-z-]+\n  failed: [^\n]*no_such_depth.pfm"
  EXPECT_STDERR "^obscura bench: 2 of 2 configurations failed [(]see above[)]\n$")
# A size whose depth texture (guard band included) is past GL_MAX_TEXTURE_SIZE is a usage error, for bench before the
# first size is timed (it ran the sizes before it and then lost them, exit 1).
obscura_cli_command_test(bench_size_past_max_texture_size 2
  "bench|--scene|analytic|--sizes|96x54,16384x9000|--guard-band|0.99|--methods|hbao|--frames|1|--warmup|0|--json|bench.json"
  GL EXPECT_STDERR "^obscura: 16384x9000 with guard band 0.99 needs a [0-9]+x[0-9]+ depth texture, past this GL context's GL_MAX_TEXTURE_SIZE of [0-9]+: [^\n]*\n$")
obscura_cli_command_test(render_size_past_max_texture_size 2
  "render|--scene|analytic|--size|16384x9000|--guard-band|0.99|--out|ao.png"
  GL EXPECT_STDERR "^obscura: 16384x9000 with guard band 0.99 needs [^\n]*GL_MAX_TEXTURE_SIZE")
if(NOT OBSCURA_CLI_COMMANDS_GPU)
  # llvmpipe's depth textures take 4 samples at most: --msaa 32 is a usage error (it was exit 1).
  obscura_cli_command_test(render_msaa_past_the_limit 2 "render|--scene|analytic|--size|32x18|--msaa|32|--out|ao.png"
    GL EXPECT_STDERR "^obscura: MSAA 32 exceeds the context's limit of [0-9]+ [(]see 'obscura --help'[)]\n$")
endif()
# truth describes the falloff it weighs hits with and no thickness: the geometry truth has the scene's own (it printed
# FFAO's 0.4 m).
obscura_cli_command_test(truth_falloff_without_thickness 0
  "truth|--scene|analytic|--size|32x18|--rays|1|--falloff|ffao|--out|truth.pfm"
  GL EXPECT_FILES "truth.pfm" EXPECT_STDOUT "seed 1, falloff exponential r=1 m\n")
# A class without pixels in a pair of frames has no flicker: "-" and null (it printed 0.00000, a perfect score).
# --classes 0.001 leaves the halo empty.
obscura_cli_command_test(compare_classes_empty_class_flicker 0
  "compare|${scene}|--methods|hbao|--truth-rays|4|--classes|0.001|--orbit|4|--frames|2|--json|report.json"
  GL CHECK classes_empty EXPECT_STDOUT "halo 0 px[^\n]*\n[^\n]*\nhbao +[0-9.]+ +[-+][0-9.]+ +[0-9.]+ +- +- +- +[0-9.]+ ")
# The screen-space reference traces rays of its own: a REFERENCE method compared with it has an error (its image was
# the reference's own, 0.00000 and PSNR inf, whatever its ray count).
obscura_cli_command_test(compare_reference_method_against_screen_truth 0
  "compare|${scene}|--methods|reference:rays=16|--truth|screen|--reference-rays|16"
  GL EXPECT_STDOUT "\nreference:rays=16 +[0-9.]+ +[0-9.]+ +0[.]0*[1-9][0-9]* ")
# Settings the SDK refuses as a whole are a usage error saying why, before any GL: the table falloff without
# its table says to give falloff_table.
obscura_cli_command_test(compare_refused_settings_say_why 2
  "compare|--scene|analytic|--size|160x90|--reference-rays|1|--methods|hbao,ffao:falloff=4"
  EXPECT_STDERR "^obscura: method spec 'ffao:falloff=4': falloff=table needs falloff_table, which is all zero: give it as falloff_table=V0/V1/.../V15 [^\n]*or falloff_table=@FILE[^\n]*\n$")
# Value names, derived settings and the falloff table through the CLI's specs: K = 32 from the preset's name,
# the table inline and from a file (tests/cli/data/falloff_table.txt: commas, spaces and newlines).
obscura_cli_command_test(render_enum_names_and_derived 0
  "render|${scene}|--method|lsao:preset=k32:pattern=aligned:tangent_strategy=fixed|--out|ao.png|--json|render.json"
  GL CHECK preset EXPECT_FILES "ao.png"
  EXPECT_STDOUT "preset +k32\n +pattern +aligned\n +directions +32 [(]derived[)]\n +step_length +4.69 px [(]derived[)]")
# The settings printed and reported are the ones the renderer derives: LSAO's segments (128 steps) with the GPU code
# paths (and on a GPU), whole lines (-1) on a CPU rasteriser's own paths. --gpu-code-paths renders those variants.
obscura_cli_command_test(render_gpu_code_paths 0
  "render|${scene}|--method|lsao|--gpu-code-paths|--out|ao.png|--json|render.json"
  GL EXPECT_FILES "ao.png|render.json" EXPECT_STDOUT "segment_steps +128 [(]derived[)]
")
if(NOT OBSCURA_CLI_COMMANDS_GPU)
  obscura_cli_command_test(render_derives_for_the_cpu_rasteriser 0
    "render|${scene}|--method|lsao|--out|ao.png"
    GL EXPECT_FILES "ao.png" EXPECT_STDOUT "segment_steps +-1 [(]derived[)]
")
endif()
obscura_cli_command_test(compare_gpu_code_paths 0
  "compare|${scene}|--methods|lsao,gtao|--gpu-code-paths|--truth-rays|4|--out-dir|out"
  GL EXPECT_FILES "out/1_lsao.png|out/2_gtao.png")
obscura_cli_command_test(render_falloff_table_inline 0
  "render|${scene}|--method|reference:rays=4:falloff=table:falloff_table=1/0.95/0.9/0.8/0.7/0.6/0.5/0.4/0.3/0.2/0.15/0.1/0.05/0.02/0.01/0|--out|ao.png"
  GL EXPECT_FILES "ao.png"
  EXPECT_STDOUT "falloff +table\n.*falloff_table +1/0.95/0.9/0.8/0.7/0.6/0.5/0.4/0.3/0.2/0.15/0.1/0.05/0.02/0.01/0\n")
obscura_cli_command_test(render_falloff_table_file 0
  "render|${scene}|--method|ffao:falloff=table:falloff_table=@${OBSCURA_CLI_COMMANDS_DIR}/data/falloff_table.txt|--out|ao.png|--json|render.json"
  GL CHECK table EXPECT_FILES "ao.png"
  EXPECT_STDOUT "falloff_table +1/0.95/0.9/0.8/0.7/0.6/0.5/0.4/0.3/0.2/0.15/0.1/0.05/0.02/0.01/0\n")
obscura_cli_command_test(demo 0 "demo|--truth-rays|4|--out-dir|demo"
  GL EXPECT_FILES "demo/1_hbao.png|demo/1_hbao_error_geometry.png|demo/geometry_truth_1.png|demo/contact_sheet.png"
  EXPECT_STDOUT "scene: atrium[^\n]*640x360.*errors against the geometry truth")
# tune: a small real search (one key, 4 evaluations, 64x36, a 16-ray truth; under a second on llvmpipe) from
# HBAO at power 3 (too dark: the search halves it within its first steps) under a budget of 100 times HBAO's own
# cost, so the budget, the second timing and the report all run; the best spec it prints renders. (At 64x36 a frame
# takes about a millisecond: under the suite's parallel load a 2x budget rejected the better candidate in CI.)
obscura_cli_command_test(tune_small 0
  "tune|--method|hbao:power=3|--scenes|analytic|--size|64x36|--keys|power|--evaluations|4|--truth-rays|16|--budget|100x:hbao|--json|tune.json"
  GL CHECK tune EXPECT_FILES "tune.json"
  EXPECT_STDOUT "searched [(]1[)]: power [[]0.001, 16[]] log\n.*\n +start +[0-9.]+ +[0-9.]+ +[0-9.]+ +[0-9.]+x\n +best [(]#[2-4][)] .*best spec: hbao:power=[0-9.]+\n.*obscura_default_settings[(]OBSCURA_METHOD_HBAO, &settings[)];\n +settings.hbao.power = [0-9.]+f;\n")
# The budget's own configuration costs the budget (1.000x, not timed against itself): `--budget 1.0x:M` from M keeps
# the start when nothing beats it. Until 2026-12-06 the start was timed against itself, read 1.01-1.35x in 6 of 10
# runs and was refused ("no candidate was within the budget", exit 1), or a worse candidate was reported.
obscura_cli_command_test(tune_budget_of_the_start 0
  "tune|--method|hbao|--scenes|analytic|--size|64x36|--keys|intensity|--evaluations|1|--truth-rays|4|--budget|1.0x:hbao"
  GL EXPECT_STDOUT "timed again [(]hbao, #1, [^)]*[)]: [0-9.]+ ms against [0-9.]+ ms, 1[.]000x: within the budget
.*best spec: hbao
")
# A start whose fields hold 0 for "default" (steps, blur_radius) searches from those defaults and prints them as the
# defaults: the spec and the C name the same values (until 2026-12-06 the spec read `hbao:steps=7:blur_radius=1`, the C
# set nothing, and tune warned that the spec did not read back).
obscura_cli_command_test(tune_start_zero_means_default 0
  "tune|--method|hbao:steps=0:blur_radius=0|--scenes|analytic|--size|64x36|--keys|power|--evaluations|2|--truth-rays|4"
  GL EXPECT_STDOUT "best spec: hbao\n")
# tune on a studio's captures: the capture written by truth (64x36, 16 rays, HBAO's falloff), then tune from HBAO at
# power 3 on it (check tune_capture: the objective is the capture's own error, render --depth against its truth
# over the non-sky pixels).
obscura_cli_command_test(tune_capture 0
  "truth|--scene|analytic|--size|64x36|--rays|16|--falloff|hbao|--out|truth.pfm|--depth-out|depth.pfm"
  GL CHECK tune_capture EXPECT_FILES "truth.pfm|depth.pfm")
# truth: a capture (linear depth + truth) that render --depth reads back as the scene itself.
obscura_cli_command_test(truth_capture 0
  "truth|${scene}|--rays|16|--falloff|hbao|--out|truth.pfm|--depth-out|depth.pfm|--png|truth.png"
  GL CHECK truth EXPECT_FILES "truth.pfm|depth.pfm|truth.png" EXPECT_STDOUT "traced [0-9]+ rays")
# The widest guard band a scene takes is one --depth reads back too: the capture's read-back command runs.
obscura_cli_command_test(truth_capture_widest_guard_band 0
  "truth|${scene}|--guard-band|0.995|--rays|4|--falloff|hbao|--out|truth.pfm|--depth-out|depth.pfm"
  GL CHECK truth EXPECT_FILES "truth.pfm|depth.pfm" EXPECT_STDOUT "--guard-band 0.995 ")
# A camera looking straight down its up vector (+Y) takes another (-Z, as the "top" viewpoints do) rather than a
# NaN view matrix: truth writes its capture, render its image, and compare finds geometry to measure (it refuses
# a view of sky only).
obscura_cli_command_test(truth_camera_straight_down 0
  "truth|--scene|analytic|--size|64x36|--eye|0,10,0|--target|0,0,0|--rays|1|--out|truth.pfm|--depth-out|depth.pfm"
  GL EXPECT_FILES "truth.pfm|depth.pfm")
obscura_cli_command_test(render_camera_straight_down 0
  "render|--scene|analytic|--size|64x36|--eye|0,10,0|--target|0,0,0|--out|ao.png" GL EXPECT_FILES "ao.png")
obscura_cli_command_test(compare_camera_straight_down 0
  "compare|--scene|analytic|--size|64x36|--eye|0,10,0|--target|0,0,0|--methods|hbao|--truth-rays|1"
  GL EXPECT_FILES "compare-output/1_hbao.png" EXPECT_STDOUT "over [1-9][0-9]* geometry pixels")

# ---- Lists and help (no GL) --------------------------------------------------------------------------
obscura_cli_command_test(list_scenes 0 "--list-scenes" EXPECT_STDOUT "atrium +available[^\n]*\n[^\n]*viewpoints: default")
obscura_cli_command_test(list_methods 0 "--list-methods" EXPECT_STDOUT "hbao +available\n")
obscura_cli_command_test(list_settings 0 "--list-settings" EXPECT_STDOUT "hbao\n[^\n]*default[^\n]*\n +radius +float +1 ")
obscura_cli_command_test(list_settings_method 0 "--list-settings|reference" EXPECT_STDOUT "^reference\n[^\n]*\n +radius")
# Enums show their default by name and list their names; derived settings say so; arrays are float[N].
obscura_cli_command_test(list_settings_enums_derived_arrays 0 "--list-settings|ffao"
  EXPECT_STDOUT "\n +falloff +enum +exponential +1 +4 +[{]rho0, inverse_quadratic, exponential, table[}] .*\n +decay_rate +float +derived +1e-10 +1e[+]08 +m\\^2 .*\n +geometry +enum +peaks +1 +2 +[{]peaks, mipmap[}] .*\n +falloff_table +float\\[16\\] +none +0 +1 +16 values, V0/V1/.../V15 or @FILE: ")
obscura_cli_command_test(list_settings_lsao_preset 0 "--list-settings|lsao"
  EXPECT_STDOUT "\n +preset +enum +derived +1 +6 +[{]k8, k16, k24, k32, k8_figure1, k16_figure13[}].*\n +directions +int +derived +1 +64 ")
obscura_cli_command_test(help 0 "--help" EXPECT_STDOUT "obscura compare[^\n]*--methods")
obscura_cli_command_test(help_compare_frames 0 "--help"
  EXPECT_STDOUT "by the frames since[.] --motion-vectors and\n  --converged need --frames; [^\n]*\n  --strip writes ")
obscura_cli_command_test(help_tune_never_searched 0 "--help"
  EXPECT_STDOUT "not temporal accumulation [(]temporal[.][*], FFAO's frame_split: tune weighs one frame[)].*--keys [^.]*it refuses the scheduling, noise, temporal[.][*] and frame_split ones[)]")

# ---- Bad arguments: exit 2 and one line on stderr, before any GL -----------------------------------------
obscura_cli_command_test(unknown_option 2 "render|--out|ao.png|--no-such-option")
obscura_cli_command_test(unknown_command 2 "frobnicate")
obscura_cli_command_test(unknown_method 2 "compare|--methods|hbao,nosuch")
obscura_cli_command_test(unknown_key 2 "render|--method|hbao:directions=8:no_such_key=1|--out|ao.png")
obscura_cli_command_test(out_of_range 2 "render|--method|hbao:directions=99|--out|ao.png")
obscura_cli_command_test(not_whole_number 2 "render|--method|hbao:steps=2.5|--out|ao.png")
obscura_cli_command_test(bad_toggle 2 "render|--method|hbao:blur=maybe|--out|ao.png")
obscura_cli_command_test(unknown_enum_name 2 "render|--method|ffao:falloff=expo|--out|ao.png"
  EXPECT_STDERR "^obscura: ffao falloff: 'expo' is not one of its values [(]valid: rho0, inverse_quadratic, exponential, table, or their numbers 1 to 4[)][^\n]*\n$")
obscura_cli_command_test(enum_out_of_range 2 "render|--method|lsao:preset=7|--out|ao.png"
  EXPECT_STDERR "^obscura: lsao preset=7 is outside \\[1, 6\\] [(]k8, k16, k24, k32, k8_figure1, k16_figure13[)][^\n]*\n$")
obscura_cli_command_test(falloff_table_wrong_count 2 "render|--method|ffao:falloff=table:falloff_table=1/0.5/0|--out|ao.png"
  EXPECT_STDERR "^obscura: ffao falloff_table: 3 values, expected 16 [(]falloff_table=V0/V1/.../V15 or falloff_table=@FILE[)][^\n]*\n$")
obscura_cli_command_test(falloff_table_out_of_range 2
  "render|--method|reference:falloff=table:falloff_table=1/1.5/1/1/1/1/1/1/1/1/1/1/1/1/1/1|--out|ao.png"
  EXPECT_STDERR "^obscura: reference falloff_table\\[1\\] = 1.5 is outside \\[0, 1\\][^\n]*\n$")
obscura_cli_command_test(falloff_table_missing_file 2 "render|--method|ffao:falloff=table:falloff_table=@no_such_table.txt|--out|ao.png"
  EXPECT_STDERR "^obscura: ffao falloff_table: cannot open 'no_such_table.txt'[^\n]*\n$")
obscura_cli_command_test(table_falloff_without_table 2 "render|--method|reference:falloff=table|--out|ao.png"
  EXPECT_STDERR "^obscura: method spec 'reference:falloff=table': falloff=table needs falloff_table[^\n]*\n$")
obscura_cli_command_test(settings_that_do_not_go_together 2 "render|--method|ffao:sectors=9|--out|ao.png"
  EXPECT_STDERR "^obscura: method spec 'ffao:sectors=9' is refused: ffao.sectors = 9: K must be even[^\n]*\n$")
obscura_cli_command_test(empty_method_entry 2 "compare|--methods|hbao,,hbao:blur=off")
obscura_cli_command_test(set_key_of_no_method 2 "compare|--methods|hbao|--set|no_such_key=1")
obscura_cli_command_test(unknown_scene 2 "render|--scene|no_such_scene|--out|ao.png")
obscura_cli_command_test(depth_with_size 2 "render|--depth|plane.pfm|--size|64x36|--out|ao.png")
obscura_cli_command_test(orbit_without_frames 2 "compare|--orbit|4" EXPECT_STDERR "--orbit DEG needs --frames N")
obscura_cli_command_test(unknown_truth 2 "compare|--truth|nosuch" EXPECT_STDERR "unknown --truth 'nosuch' [(]valid: geometry, screen, both[)]")
obscura_cli_command_test(compare_classes_not_a_number 2 "compare|--classes|abc"
  EXPECT_STDERR "^obscura: --classes [(]radius in metres[)]: 'abc' is not a number [^\n]*\n$")
obscura_cli_command_test(compare_classes_three_values 2 "compare|--classes|1,0.3,2" EXPECT_STDERR "is not RADIUS_M[[],THICKNESS_M[]]")
obscura_cli_command_test(compare_classes_orthographic 2 "compare|--scene|analytic|--projection|ortho|--classes"
  EXPECT_STDERR "--classes needs a perspective projection")
obscura_cli_command_test(depth_file_has_no_geometry_truth 2
  "compare|--depth|${OBSCURA_CLI_COMMANDS_DIR}/data/plane_64x36_linear.pfm|--truth|both"
  EXPECT_STDERR "needs a scene's triangles")
obscura_cli_command_test(truth_of_a_depth_file 2 "truth|--depth|x.pfm|--out|t.pfm" EXPECT_STDERR "needs a scene's triangles")
obscura_cli_command_test(truth_without_out 2 "truth|--scene|analytic" EXPECT_STDERR "truth needs --out")
obscura_cli_command_test(truth_depth_out_needs_single_sample 2
  "truth|--scene|analytic|--msaa|2|--out|t.pfm|--depth-out|d.pfm" EXPECT_STDERR "needs a single-sample depth buffer")
obscura_cli_command_test(tune_unknown_key 2 "tune|--method|hbao|--scenes|analytic|--keys|power,no_such_key"
  EXPECT_STDERR "^obscura: --keys: hbao has no setting 'no_such_key' [(]its settings: radius, falloff_c, [^\n]*[)] [(]see 'obscura --help'[)]\n$")
obscura_cli_command_test(tune_bad_budget 2 "tune|--method|hbao|--scenes|analytic|--budget|1.0:hbao"
  EXPECT_STDERR "^obscura: --budget: '1.0:hbao' is not RATIOx:SPEC [(]e.g. 1.0x:hbao[^\n]*\n$")
obscura_cli_command_test(tune_key_not_searched 2 "tune|--method|gtao|--scenes|analytic|--keys|power,frame_index"
  EXPECT_STDERR "^obscura: --keys: frame_index is not searched: it moves the noise pattern only[^\n]*\n$")
obscura_cli_command_test(tune_temporal_start 2 "tune|--method|hbao:temporal.enabled=on|--scenes|analytic"
  EXPECT_STDERR "^obscura: --method hbao:temporal.enabled=on: tune weighs one frame per scene")
obscura_cli_command_test(tune_json_unwritable 2
  "tune|--method|hbao|--scenes|analytic|--json|no_such_dir/tune.json"
  EXPECT_STDERR "^obscura: --json: cannot open ")
obscura_cli_command_test(tune_without_scenes 2 "tune|--method|hbao" EXPECT_STDERR "^obscura: tune needs --scenes ")
obscura_cli_command_test(tune_captures_without_truths 2 "tune|--method|hbao|--captures|d.pfm"
  EXPECT_STDERR "^obscura: --captures DEPTH.pfm,... and --truths TRUTH.pfm,... go together")
obscura_cli_command_test(tune_captures_and_truths_differ 2 "tune|--method|hbao|--captures|a.pfm,b.pfm|--truths|t.pfm"
  EXPECT_STDERR "^obscura: --captures names 2 depth files and --truths 1 truths")
obscura_cli_command_test(tune_scenes_and_captures 2 "tune|--method|hbao|--scenes|analytic|--captures|d.pfm|--truths|t.pfm"
  EXPECT_STDERR "^obscura: --scenes and --captures are alternatives")
obscura_cli_command_test(tune_captures_falloff_key 2 "tune|--method|hbao|--captures|d.pfm|--truths|t.pfm|--keys|power,radius"
  EXPECT_STDERR "^obscura: --keys radius: a capture's truth was traced with one falloff")
obscura_cli_command_test(tune_captures_with_normals 2 "tune|--method|hbao|--captures|d.pfm|--truths|t.pfm|--normals"
  EXPECT_STDERR "^obscura: --normals does not apply to --captures")
obscura_cli_command_test(tune_captures_with_truth_rays 2 "tune|--method|hbao|--captures|d.pfm|--truths|t.pfm|--truth-rays|16"
  EXPECT_STDERR "^obscura: --truth-rays does not apply to --captures")
obscura_cli_command_test(tune_captures_with_depth 2 "tune|--method|hbao|--depth|d.pfm"
  EXPECT_STDERR "^obscura: tune takes depth buffers as --captures")
# An option's value is never the next option (`--json --sync-timing` wrote a report named "--sync-timing" and timed
# without sync; `bench --json --csv b.csv` said b.csv was unknown); a negative number is a value.
obscura_cli_command_test(option_value_is_another_option 2
  "compare|--scene|analytic|--size|32x18|--methods|hbao|--truth-rays|1|--json|--sync-timing"
  EXPECT_STDERR "^obscura: --json needs a value, not the option '--sync-timing' [(]give --json=VALUE [^\n]*\n$")
obscura_cli_command_test(bench_option_value_is_another_option 2 "bench|--json|--csv|b.csv"
  EXPECT_STDERR "^obscura: --json needs a value, not the option '--csv'")
obscura_cli_command_test(negative_number_is_a_value 2 "render|--eye|-1,2,3|--out|ao.png"
  EXPECT_STDERR "^obscura: --eye and --target go together")
# Output files are checked before the work (truth left half a capture, compare and bench lost minutes of it).
obscura_cli_command_test(compare_json_unwritable 2
  "compare|--scene|analytic|--size|32x18|--methods|hbao|--truth-rays|1|--json|no_such_dir/report.json"
  EXPECT_STDERR "^obscura: --json: cannot open no_such_dir/report.json for writing")
obscura_cli_command_test(compare_out_dir_uncreatable 2
  "compare|--scene|analytic|--size|32x18|--methods|hbao|--truth-rays|1|--out-dir|/dev/null/out"
  EXPECT_STDERR "^obscura: --out-dir: cannot create the directory /dev/null/out")
obscura_cli_command_test(truth_depth_out_unwritable 2
  "truth|--scene|analytic|--size|32x18|--rays|1|--out|truth.pfm|--depth-out|no_such_dir/depth.pfm"
  EXPECT_STDERR "^obscura: --depth-out: cannot open no_such_dir/depth.pfm for writing")
obscura_cli_command_test(bench_csv_unwritable 2
  "bench|--scene|analytic|--sizes|32x18|--frames|1|--warmup|0|--csv|no_such_dir/bench.csv"
  EXPECT_STDERR "^obscura: --csv: cannot open no_such_dir/bench.csv for writing")
# Two outputs naming one file: one would overwrite the other.
obscura_cli_command_test(truth_outputs_name_one_file 2
  "truth|--scene|analytic|--size|32x18|--rays|1|--out|a.pfm|--depth-out|./a.pfm"
  EXPECT_STDERR "^obscura: --out a.pfm and --depth-out ./a.pfm name the same file")
obscura_cli_command_test(render_outputs_name_one_file 2 "render|--scene|analytic|--size|32x18|--out|ao.png|--json|ao.png"
  EXPECT_STDERR "^obscura: --out ao.png and --json ao.png name the same file")
# A depth file's options given to a command without --depth say where they belong with it.
obscura_cli_command_test(tune_depth_option_with_scenes 2 "tune|--method|hbao|--scenes|analytic|--near|0.2"
  EXPECT_STDERR "^obscura: --near is a depth option of --captures")
obscura_cli_command_test(demo_depth_option 2 "demo|--depth-kind|linear"
  EXPECT_STDERR "^obscura: --depth-kind does not apply to demo [(]it renders the atrium")
obscura_cli_command_test(truth_depth_option 2 "truth|--scene|analytic|--near|0.2|--out|t.pfm"
  EXPECT_STDERR "^obscura: --near does not apply to truth")
# A setting given twice, or by two options, is refused (the last won silently).
obscura_cli_command_test(diff_tolerance_key_twice 2 "diff|a.png|b.png|--tolerance|mean=0.001,mean=0.5"
  EXPECT_STDERR "^obscura diff: --tolerance gives mean twice")
obscura_cli_command_test(compare_temporal_and_set_temporal 2 "compare|--temporal|on|--set|temporal.enabled=off"
  EXPECT_STDERR "^obscura: --temporal on and --set temporal.enabled=off both set temporal.enabled")
obscura_cli_command_test(set_key_twice 2 "compare|--methods|hbao|--set|radius=1|--set|radius=2"
  EXPECT_STDERR "^obscura: --set radius given more than once")
obscura_cli_command_test(tune_scene_twice 2 "tune|--method|hbao|--scenes|analytic,analytic@default"
  EXPECT_STDERR "^obscura: --scenes names the view analytic@default twice")
# Motion vectors are rasterised single-sample only: with --msaa a usage error before any GL, whether asked for or the
# animated scene's default.
obscura_cli_command_test(compare_motion_vectors_msaa 2 "compare|--scene|analytic|--motion-vectors|on|--frames|3|--msaa|2"
  EXPECT_STDERR "^obscura: motion vectors [^\n]*need a single-sample depth buffer: drop --msaa 2 or give --motion-vectors off")
obscura_cli_command_test(compare_animated_scene_msaa 2 "compare|--scene|sliding|--frames|3|--msaa|4"
  EXPECT_STDERR "^obscura: motion vectors [^\n]*the default on an animated scene[^\n]*: drop --msaa 4 ")
# Options that would do nothing are refused, as --converged without --frames is (the commands are small, so that
# without the check they finish quickly with exit 0).
obscura_cli_command_test(compare_motion_vectors_without_frames 2
  "compare|--scene|analytic|--size|32x18|--methods|hbao|--truth-rays|1|--motion-vectors|on"
  EXPECT_STDERR "--motion-vectors needs --frames N")
obscura_cli_command_test(compare_truth_rays_without_geometry_truth 2
  "compare|--scene|analytic|--size|32x18|--methods|hbao|--reference-rays|1|--truth|screen|--truth-rays|4"
  EXPECT_STDERR "^obscura: --truth-rays sets the geometry truth, which --truth screen does not trace")
obscura_cli_command_test(compare_truth_seed_without_geometry_truth 2
  "compare|--scene|analytic|--size|32x18|--methods|hbao|--reference-rays|1|--truth|screen|--truth-seed|4"
  EXPECT_STDERR "^obscura: --truth-seed sets the geometry truth")
obscura_cli_command_test(compare_reference_rays_without_screen_truth 2
  "compare|--scene|analytic|--size|32x18|--methods|hbao|--truth-rays|1|--reference-rays|4"
  EXPECT_STDERR "^obscura: --reference-rays sets the screen-space reference, which --truth geometry does not render")
# diff reads a .pfm name as PFM and any other as PNG: a file named for the other format is refused.
obscura_cli_command_test(render_out_named_pfm 2 "render|--scene|analytic|--size|32x18|--out|ao.pfm"
  EXPECT_STDERR "^obscura: --out writes PNG, but 'ao.pfm' is named as a PFM file [^\n]*; --pfm writes PFM ")
obscura_cli_command_test(truth_out_named_png 2 "truth|--scene|analytic|--size|32x18|--rays|1|--out|truth.png"
  EXPECT_STDERR "^obscura: --out writes PFM, but 'truth.png' is not named .pfm [^\n]*; --png writes PNG ")
# A guard band of 1 or more: refused for scenes as for depth files (which take [0, 1)).
obscura_cli_command_test(scene_guard_band_one 2 "render|--scene|analytic|--size|32x18|--guard-band|1|--out|ao.png"
  EXPECT_STDERR "^obscura: --guard-band: 1 is outside \\[0, 1[)]")
obscura_cli_command_test(depth_file_guard_band_one 2 "render|--depth|plane.pfm|--guard-band|1|--out|ao.png"
  EXPECT_STDERR "^obscura: --guard-band: 1 is outside \\[0, 1[)]")
# Numbers are decimal: no '+', no leading space, no hexadecimal (strtol and strtod took all three).
obscura_cli_command_test(integer_with_plus_sign 2 "render|--scene|analytic|--size|+32x18|--out|ao.png"
  EXPECT_STDERR "^obscura: --size [(]width[)]: '[+]32' is not an integer")
obscura_cli_command_test(integer_with_leading_space 2 "render|--scene|analytic|--size| 32x18|--out|ao.png"
  EXPECT_STDERR "^obscura: --size [(]width[)]: ' 32' is not an integer")
obscura_cli_command_test(hexadecimal_float_option 2
  "compare|--scene|analytic|--size|32x18|--methods|hbao|--truth-rays|1|--frames|2|--orbit|0x10"
  EXPECT_STDERR "^obscura: --orbit: '0x10' is not a number")
obscura_cli_command_test(hexadecimal_spec_value 2 "render|--scene|analytic|--size|32x18|--method|hbao:steps=0x10|--out|ao.png"
  EXPECT_STDERR "^obscura: hbao steps: '0x10' is not a number")
# JSON reports stay UTF-8 whatever the file names (no GL: diff).
obscura_cli_command_test(json_report_file_name_not_utf8 0 "" CHECK json_utf8)
# A camera that sees only sky has no geometry pixel to measure: refused with a reason, not a perfect score.
obscura_cli_command_test(compare_sky_only_view 1
  "compare|--scene|analytic|--size|64x36|--eye|0,2,0|--target|0,10,5|--methods|hbao|--truth-rays|1"
  GL EXPECT_STDERR "shows no geometry [(]every pixel is sky[)]")
# A method the library does not implement (found with --list-methods): exit 1, naming it. Every method is built in
# today, so ctest reports it as skipped (not passed) until a build leaves one out.
obscura_cli_command_test(unavailable_method 1 "" CHECK unavailable)
set_tests_properties(obscura_cli.unavailable_method PROPERTIES SKIP_REGULAR_EXPRESSION "every method is available: nothing to check")
