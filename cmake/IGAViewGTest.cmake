# GoogleTest from the system (Debian's libgtest-dev) or, where none is installed (the GPU
# machine), from sources given by IGAVIEW_GTEST_SOURCE_DIR (defaults to a carried .deps folder).
find_package(GTest QUIET)
if(NOT GTest_FOUND)
  set(IGAVIEW_GTEST_SOURCE_DIR "${CMAKE_CURRENT_LIST_DIR}/../.deps/googletest"
    CACHE PATH "GoogleTest sources used when no installed GTest is found")
  if(NOT EXISTS "${IGAVIEW_GTEST_SOURCE_DIR}/CMakeLists.txt")
    message(FATAL_ERROR "GoogleTest not found: install libgtest-dev or set IGAVIEW_GTEST_SOURCE_DIR")
  endif()
  set(INSTALL_GTEST OFF CACHE BOOL "" FORCE)
  add_subdirectory("${IGAVIEW_GTEST_SOURCE_DIR}" "${CMAKE_BINARY_DIR}/googletest" EXCLUDE_FROM_ALL)
  add_library(GTest::gtest ALIAS gtest)
  add_library(GTest::gtest_main ALIAS gtest_main)
endif()
include(GoogleTest)

# The tests' main: GoogleTest's, and a scratch directory for each test process
# (Testing/ScratchDirectory.cxx).
if(NOT TARGET igaTestMain)
  add_library(igaTestMain INTERFACE)
  target_sources(igaTestMain INTERFACE ${CMAKE_CURRENT_LIST_DIR}/../Testing/ScratchDirectory.cxx)
  target_link_libraries(igaTestMain INTERFACE GTest::gtest_main)
endif()
