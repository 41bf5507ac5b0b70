# igaview-generate-data --help prints the usage and exits 0, writing nothing; an option where
# the output directory belongs is refused, writing nothing either.
execute_process(COMMAND ${COMMAND} --help RESULT_VARIABLE rc OUTPUT_VARIABLE out)
if(NOT rc EQUAL 0 OR NOT out MATCHES "^usage: igaview-generate-data OUTPUT_DIRECTORY")
  message(FATAL_ERROR "--help: exit ${rc}, output: ${out}")
endif()
execute_process(COMMAND ${COMMAND} --series 2 RESULT_VARIABLE rc ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "the first argument must be the output directory, got '--series'")
  message(FATAL_ERROR "--series as the directory: exit ${rc}, stderr: ${err}")
endif()
if(EXISTS "${CMAKE_CURRENT_BINARY_DIR}/--help" OR EXISTS "${CMAKE_CURRENT_BINARY_DIR}/--series")
  message(FATAL_ERROR "a folder named after an option was written")
endif()
