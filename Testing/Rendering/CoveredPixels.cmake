# covered_pixels(COMMAND EXPECT RESULT): runs COMMAND (a ;-list, through the retry on X connection
# failures), fails unless it exits 0 with output matching EXPECT and a "N pixels covered", and
# sets RESULT to the last N it printed.
function(covered_pixels command expect result)
  execute_process(COMMAND ${CMAKE_COMMAND} "-DCOMMAND=${command}" "-DEXPECT=${expect}"
    -P ${CMAKE_CURRENT_LIST_DIR}/../RetryOnXFailure.cmake
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  message("${out}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "the command failed")
  endif()
  string(REGEX MATCHALL "[0-9]+ pixels covered" counts "${out}")
  list(LENGTH counts found)
  if(found EQUAL 0)
    message(FATAL_ERROR "the command printed no 'N pixels covered'")
  endif()
  list(GET counts -1 last)
  string(REGEX MATCH "^[0-9]+" covered "${last}")
  set(${result} ${covered} PARENT_SCOPE)
endfunction()
