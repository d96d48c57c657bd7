# write_if_changed(FILE TEXT): writes TEXT to FILE unless FILE holds it
# already, so that a generated source that did not change rebuilds
# nothing. Included by the build's generator scripts.
function(write_if_changed file text)
  if(EXISTS "${file}")
    file(READ "${file}" old)
    if(old STREQUAL text)
      return()
    endif()
  endif()
  file(WRITE "${file}" "${text}")
endfunction()
