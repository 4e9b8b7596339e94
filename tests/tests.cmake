# Unit tests (C, one executable per module), CLI tests (shell), and the
# scripted regression tests (caustica test), all run by ctest.
foreach(name math image gltf gltf_hostile gltf_pose graph scene gl texture texture_lod tangents optics shading program illumination plot lua_pattern photon_map sppm_restart volume_grid huge_pages)
  add_executable(test_${name} tests/unit/test_${name}.c)
  target_link_libraries(test_${name} PRIVATE caustica_core)
  add_test(NAME unit_${name} COMMAND test_${name})
  set_tests_properties(unit_${name} PROPERTIES ENVIRONMENT "CAUSTICA_ROOT=${CMAKE_SOURCE_DIR};CAUSTICA_CACHE=${CMAKE_BINARY_DIR}/cache")
endforeach()

file(GLOB CLI_TESTS ${CMAKE_SOURCE_DIR}/tests/cli/*_test.sh)
foreach(script ${CLI_TESTS})
  get_filename_component(name ${script} NAME_WE)
  add_test(NAME cli_${name} COMMAND bash ${script} $<TARGET_FILE:caustica> ${CMAKE_SOURCE_DIR})
  # exit 77: skipped (a test whose tools are not on this machine says why)
  set_tests_properties(cli_${name} PROPERTIES ENVIRONMENT "CAUSTICA_ROOT=${CMAKE_SOURCE_DIR};CAUSTICA_CACHE=${CMAKE_BINARY_DIR}/cache"
                       SKIP_RETURN_CODE 77)
endforeach()

file(GLOB LUA_TESTS ${CMAKE_SOURCE_DIR}/tests/lua/*_test.lua)
foreach(script ${LUA_TESTS})
  get_filename_component(name ${script} NAME_WE)
  add_test(NAME lua_${name} COMMAND caustica test ${script} WORKING_DIRECTORY ${CMAKE_SOURCE_DIR})
  set_tests_properties(lua_${name} PROPERTIES ENVIRONMENT "CAUSTICA_ROOT=${CMAKE_SOURCE_DIR};CAUSTICA_CACHE=${CMAKE_BINARY_DIR}/cache")
endforeach()

# Fuzz inputs replayed in every build: the seed corpus and each crash kept
# from fuzzing (tests/fuzz/README.md).
foreach(name gltf script bench_csv reference_part test_report)
  add_executable(replay_${name} tests/fuzz/replay_main.c tests/fuzz/fuzz_${name}.c)
  target_link_libraries(replay_${name} PRIVATE caustica_core)
endforeach()
add_test(NAME fuzz_gltf_regressions COMMAND replay_gltf
         ${CMAKE_SOURCE_DIR}/tests/fuzz/corpus_gltf ${CMAKE_SOURCE_DIR}/tests/fuzz/crashes_gltf)
# The image readers: one harness each, built from one source.
set(CAUSTICA_IMAGE_FUZZ_FORMATS png jpeg exr hdr pfm)
foreach(format ${CAUSTICA_IMAGE_FUZZ_FORMATS})
  add_executable(replay_${format} tests/fuzz/replay_main.c tests/fuzz/fuzz_image_reader.c)
  target_compile_definitions(replay_${format} PRIVATE FUZZ_IMAGE_FORMAT=${format})
  target_link_libraries(replay_${format} PRIVATE caustica_core)
  add_test(NAME fuzz_${format}_regressions COMMAND replay_${format}
           ${CMAKE_SOURCE_DIR}/tests/fuzz/corpus_${format} ${CMAKE_SOURCE_DIR}/tests/fuzz/crashes_${format})
endforeach()
add_test(NAME fuzz_bench_csv_regressions COMMAND replay_bench_csv
         ${CMAKE_SOURCE_DIR}/tests/fuzz/corpus_bench_csv ${CMAKE_SOURCE_DIR}/tests/fuzz/crashes_bench_csv)
add_test(NAME fuzz_reference_part_regressions COMMAND replay_reference_part
         ${CMAKE_SOURCE_DIR}/tests/fuzz/corpus_reference_part ${CMAKE_SOURCE_DIR}/tests/fuzz/crashes_reference_part)
add_test(NAME fuzz_test_report_regressions COMMAND replay_test_report
         ${CMAKE_SOURCE_DIR}/tests/fuzz/corpus_test_report ${CMAKE_SOURCE_DIR}/tests/fuzz/crashes_test_report)
# The script corpus is made from the scene scripts (tests/fuzz/script_corpus.sh).
add_test(NAME fuzz_script_regressions COMMAND sh -c
         "${CMAKE_SOURCE_DIR}/tests/fuzz/script_corpus.sh ${CMAKE_BINARY_DIR}/corpus_script && \
          $<TARGET_FILE:replay_script> ${CMAKE_BINARY_DIR}/corpus_script ${CMAKE_SOURCE_DIR}/tests/fuzz/crashes_script")
set_tests_properties(fuzz_gltf_regressions fuzz_script_regressions PROPERTIES
                     ENVIRONMENT "CAUSTICA_ROOT=${CMAKE_SOURCE_DIR};CAUSTICA_CACHE=${CMAKE_BINARY_DIR}/cache")

# A hang fails its own test instead of holding the run until CI's limit:
# the longest test takes about 170 s beside two CPU hogs (docs/TESTING.md),
# a fuzz replay well under a second (each input also has 30 s of its own,
# tests/fuzz/replay_main.c).
get_property(CAUSTICA_ALL_TESTS DIRECTORY PROPERTY TESTS)
foreach(t ${CAUSTICA_ALL_TESTS})
  if(t MATCHES "^fuzz_")
    set_tests_properties(${t} PROPERTIES TIMEOUT 300)
  else()
    set_tests_properties(${t} PROPERTIES TIMEOUT 900)
  endif()
endforeach()
