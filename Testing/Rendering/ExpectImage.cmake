# Runs COMMAND (a ;-list, through the retry on X connection failures) and passes when it exits 0,
# its output matches EXPECT, and the image IMAGE it wrote shows as many pixels off the
# background as the last "N pixels covered" it printed, N at least MINIMUM (igaImageCoverage,
# CHECKER; with OVERLAY, at least as many: text drawn over the image). Exit code, output and
# pixels: none of them alone.
execute_process(COMMAND ${CMAKE_COMMAND} "-DCOMMAND=${COMMAND}" "-DEXPECT=${EXPECT}"
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
execute_process(COMMAND ${CHECKER} ${IMAGE} ${covered} ${MINIMUM} ${OVERLAY} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the image does not show what the engine covered")
endif()
