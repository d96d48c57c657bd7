# raw_string_literal(VAR FILE DELIM): sets VAR to FILE's text as a C++ raw
# string literal, R"DELIM(...)DELIM"; fails the build when the text holds
# the closing delimiter or a byte the literal would not carry exactly.
function(raw_string_literal var file delim)
  file(READ "${file}" text)
  # file(READ) drops carriage returns, and compilers may turn a raw
  # literal's line ends into '\n': a file they would change is refused.
  string(LENGTH "${text}" read)
  file(SIZE "${file}" size)
  if(NOT read EQUAL size)
    message(FATAL_ERROR "${file} holds a carriage return or a NUL byte: a raw string cannot carry it")
  endif()
  string(FIND "${text}" ")${delim}\"" clash)
  if(NOT clash EQUAL -1)
    message(FATAL_ERROR "${file} contains the raw-string delimiter )${delim}\"")
  endif()
  set(${var} "R\"${delim}(${text})${delim}\"" PARENT_SCOPE)
endfunction()
