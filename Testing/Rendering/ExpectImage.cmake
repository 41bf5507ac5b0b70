# Runs COMMAND (a ;-list, through the retry on X connection failures) and passes when it exits 0,
# its output matches EXPECT, and the image IMAGE it wrote shows as many pixels off the
# background as the last "N pixels covered" it printed, N at least MINIMUM (igaImageCoverage,
# CHECKER; with OVERLAY, at least as many: text drawn over the image). Exit code, output and
# pixels: none of them alone.
include(${CMAKE_CURRENT_LIST_DIR}/CoveredPixels.cmake)
covered_pixels("${COMMAND}" "${EXPECT}" covered)
execute_process(COMMAND ${CHECKER} ${IMAGE} ${covered} ${MINIMUM} ${OVERLAY} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the image does not show what the engine covered")
endif()
