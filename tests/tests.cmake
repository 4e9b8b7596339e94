# Unit tests (C, one executable per module), CLI tests (shell), and the
# scripted regression tests (caustica test), all run by ctest.
foreach(name math image gltf gltf_hostile graph scene gl)
  add_executable(test_${name} tests/unit/test_${name}.c)
  target_link_libraries(test_${name} PRIVATE caustica_core)
  add_test(NAME unit_${name} COMMAND test_${name})
  set_tests_properties(unit_${name} PROPERTIES ENVIRONMENT "CAUSTICA_ROOT=${CMAKE_SOURCE_DIR}")
endforeach()

file(GLOB CLI_TESTS ${CMAKE_SOURCE_DIR}/tests/cli/*_test.sh)
foreach(script ${CLI_TESTS})
  get_filename_component(name ${script} NAME_WE)
  add_test(NAME cli_${name} COMMAND bash ${script} $<TARGET_FILE:caustica> ${CMAKE_SOURCE_DIR})
  set_tests_properties(cli_${name} PROPERTIES ENVIRONMENT "CAUSTICA_ROOT=${CMAKE_SOURCE_DIR}")
endforeach()

file(GLOB LUA_TESTS ${CMAKE_SOURCE_DIR}/tests/lua/*_test.lua)
foreach(script ${LUA_TESTS})
  get_filename_component(name ${script} NAME_WE)
  add_test(NAME lua_${name} COMMAND caustica test ${script} WORKING_DIRECTORY ${CMAKE_SOURCE_DIR})
  set_tests_properties(lua_${name} PROPERTIES ENVIRONMENT "CAUSTICA_ROOT=${CMAKE_SOURCE_DIR}")
endforeach()

# Fuzz inputs replayed in every build: the seed corpus and each crash kept
# from fuzzing (tests/fuzz/README.md).
foreach(name gltf script)
  add_executable(replay_${name} tests/fuzz/replay_main.c tests/fuzz/fuzz_${name}.c)
  target_link_libraries(replay_${name} PRIVATE caustica_core)
  add_test(NAME fuzz_${name}_regressions COMMAND replay_${name}
           ${CMAKE_SOURCE_DIR}/tests/fuzz/corpus_${name} ${CMAKE_SOURCE_DIR}/tests/fuzz/crashes_${name})
  set_tests_properties(fuzz_${name}_regressions PROPERTIES ENVIRONMENT "CAUSTICA_ROOT=${CMAKE_SOURCE_DIR}")
endforeach()
