# Corpus replay: every fuzz target also builds, with any compiler, as a plain
# program (replay_main.cpp) that runs LLVMFuzzerTestOneInput on each file of
# its committed corpus. Registered as unit tests, so CI runs them in the
# Release pass and again under ASan/UBSan. Included from tests/CMakeLists.txt.
include(${CMAKE_CURRENT_LIST_DIR}/targets.cmake)
foreach(name ${EARC_FUZZ_TARGETS})
  add_executable(fuzz-replay-${name} ${EARC_FUZZ_DIR}/fuzz_${name}.cpp ${EARC_FUZZ_DIR}/replay_main.cpp)
  target_link_libraries(fuzz-replay-${name} PRIVATE earc)
  target_compile_options(fuzz-replay-${name} PRIVATE ${EARC_WARNINGS} ${EARC_TEST_CODE_OPTIONS})
  add_test(NAME fuzz.replay.${name} COMMAND fuzz-replay-${name} ${EARC_FUZZ_DIR}/corpus/${name})
  set_tests_properties(fuzz.replay.${name} PROPERTIES LABELS unit TIMEOUT 300)
endforeach()
