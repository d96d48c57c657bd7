# The libFuzzer targets: tests/fuzz/fuzz_<name>.cpp each define
# LLVMFuzzerTestOneInput; tests/fuzz/corpus/<name>/ is its seed corpus.
set(EARC_FUZZ_TARGETS scenario solution import path_blob)
set(EARC_FUZZ_DIR ${CMAKE_CURRENT_LIST_DIR})
