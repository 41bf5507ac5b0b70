# Runs a command and fails as it does, except that a run that failed because the X server
# refused the render window's connection ("bad X server connection", seen intermittently under
# xvfb here when tests run in parallel, with no relation to the code under test) is run again,
# up to 8 times, after a pause that grows (1, 2, ..., 7 s): three immediate retries once failed
# in a row, and five over 10 s did once on a machine loaded by two fuzzers besides the tests. The command is COMMAND (a ;-list) or, when this script serves as a test
# executable's CROSSCOMPILING_EMULATOR, the arguments after the script. Its output goes to
# standard output (gtest_discover_tests reads the test list from there). With EXPECT (a
# regular expression) the output must match it too: a test passes on its exit code and its
# output, never on its output alone.
if(NOT DEFINED COMMAND)
  math(EXPR last "${CMAKE_ARGC} - 1")
  foreach(i RANGE 3 ${last})
    list(APPEND COMMAND "${CMAKE_ARGV${i}}")
  endforeach()
endif()
foreach(attempt RANGE 1 8)
  execute_process(COMMAND ${COMMAND} RESULT_VARIABLE result OUTPUT_VARIABLE out
    ERROR_VARIABLE out)
  if(result EQUAL 0 OR NOT out MATCHES "bad X server connection" OR attempt EQUAL 8)
    break()
  endif()
  message(STATUS "attempt ${attempt}: the X server refused a connection; running again")
  execute_process(COMMAND ${CMAKE_COMMAND} -E sleep ${attempt})
endforeach()
execute_process(COMMAND ${CMAKE_COMMAND} -E echo "${out}")
if(NOT result EQUAL 0)
  message(FATAL_ERROR "failed (${result})")
endif()
if(DEFINED EXPECT AND NOT out MATCHES "${EXPECT}")
  message(FATAL_ERROR "exited 0, but the output does not match '${EXPECT}'")
endif()
