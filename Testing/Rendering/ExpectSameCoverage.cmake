# Runs COMMAND and OTHER (;-lists, through the retry on X connection failures) and passes when
# both exit 0 and the last "N pixels covered" each printed differ by at most TOLERANCE: two ways
# of drawing that must show the same pixels.
function(covered_pixels command result)
  execute_process(COMMAND ${CMAKE_COMMAND} "-DCOMMAND=${command}" "-DEXPECT=pixels covered"
    -P ${CMAKE_CURRENT_LIST_DIR}/../RetryOnXFailure.cmake
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  message("${out}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "the command failed")
  endif()
  string(REGEX MATCHALL "[0-9]+ pixels covered" counts "${out}")
  list(GET counts -1 last)
  string(REGEX MATCH "^[0-9]+" covered "${last}")
  set(${result} ${covered} PARENT_SCOPE)
endfunction()
covered_pixels("${COMMAND}" first)
covered_pixels("${OTHER}" second)
math(EXPR difference "${first} - ${second}")
if(difference LESS 0)
  math(EXPR difference "-${difference}")
endif()
if(difference GREATER TOLERANCE)
  message(FATAL_ERROR "${first} and ${second} pixels covered: more than ${TOLERANCE} apart")
endif()
