# One CTest test per GoogleTest suite, not per test:
#
#   mvw_gtest_suites(mvw_gl_tests TIMEOUT 600 [LABELS gl data] [SKIP_REGULAR_EXPRESSION RE])
#
# Like gtest_discover_tests in PRE_TEST mode (when CTest starts, an executable newer than its
# list is asked for its tests again), but each test suite (every TEST_F of a fixture, every
# instance of a parameterised test) runs as one process: `EXE --gtest_filter=Suite.*`. A suite's
# SetUpTestSuite (a study loaded, a phantom made, a GL context) then runs once instead of once
# per test, and a process starts once per suite: under ASan each start costs about 0.4 s and the
# fixtures several seconds (docs/testing.md, "Test time"). The CTest name is the suite's name
# (`ctest -R KnownTransform`); GoogleTest's output names every test and its result, and a
# failing suite's output is printed whole.
include_guard(GLOBAL)

set(MVW_GTEST_SUITES_SCAN ${CMAKE_CURRENT_LIST_DIR}/GTestSuitesScan.cmake)

function(mvw_gtest_suites target)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "TIMEOUT;SKIP_REGULAR_EXPRESSION" "LABELS")
  if(NOT arg_TIMEOUT)
    message(FATAL_ERROR "mvw_gtest_suites(${target}): give a TIMEOUT (seconds per suite)")
  endif()
  set(list_file ${CMAKE_CURRENT_BINARY_DIR}/${target}_suites.cmake)
  set(include_file ${CMAKE_CURRENT_BINARY_DIR}/${target}_suites_include.cmake)
  string(REPLACE ";" "," labels "${arg_LABELS}")
  # Run by CTest before it runs anything: scan when the list is missing or older than the
  # executable, then add the suites; an executable not built or not listing is a failing test.
  file(GENERATE OUTPUT ${include_file} CONTENT "\
set(exe [==[$<TARGET_FILE:${target}>]==])
set(list [==[${list_file}]==])
if(NOT EXISTS \"\${exe}\")
  add_test([==[${target}_NOT_BUILT]==] [==[${CMAKE_COMMAND}]==] -E echo [==[${target} is not built]==])
  set_tests_properties([==[${target}_NOT_BUILT]==] PROPERTIES WILL_FAIL TRUE)
  return()
endif()
if(NOT EXISTS \"\${list}\" OR \"\${exe}\" IS_NEWER_THAN \"\${list}\")
  execute_process(COMMAND [==[${CMAKE_COMMAND}]==] -D \"EXE=\${exe}\" -D \"OUT=\${list}\"
                          -D [==[TIMEOUT=${arg_TIMEOUT}]==] -D [==[LABELS=${labels}]==]
                          -D [==[SKIP_REGULAR_EXPRESSION=${arg_SKIP_REGULAR_EXPRESSION}]==]
                          -P [==[${MVW_GTEST_SUITES_SCAN}]==]
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    add_test([==[${target}_NOT_LISTED]==] [==[${CMAKE_COMMAND}]==] -E echo \"\${out}\")
    set_tests_properties([==[${target}_NOT_LISTED]==] PROPERTIES WILL_FAIL TRUE)
    return()
  endif()
endif()
include(\"\${list}\")
")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${include_file})
endfunction()
