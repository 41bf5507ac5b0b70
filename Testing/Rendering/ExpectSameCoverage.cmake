# Runs COMMAND and OTHER (;-lists, through the retry on X connection failures) and passes when
# both exit 0 and the last "N pixels covered" each printed differ by at most TOLERANCE: two ways
# of drawing that must show the same pixels.
include(${CMAKE_CURRENT_LIST_DIR}/CoveredPixels.cmake)
covered_pixels("${COMMAND}" "pixels covered" first)
covered_pixels("${OTHER}" "pixels covered" second)
math(EXPR difference "${first} - ${second}")
if(difference LESS 0)
  math(EXPR difference "-${difference}")
endif()
if(difference GREATER TOLERANCE)
  message(FATAL_ERROR "${first} and ${second} pixels covered: more than ${TOLERANCE} apart")
endif()
