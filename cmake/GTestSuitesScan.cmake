# Run for mvw_gtest_suites (cmake/GTestSuites.cmake) when CTest starts and a test executable is
# newer than its list: lists its
# tests and writes OUT, a CTest script with one add_test per suite.
#   cmake -D EXE=... -D OUT=... -D TIMEOUT=600 [-D LABELS=gl,data] [-D SKIP_REGULAR_EXPRESSION=RE]
#         -P GTestSuitesScan.cmake
# No list is left behind a failure, so the next CTest run scans again.
macro(refuse why)
  file(REMOVE ${OUT})
  message(FATAL_ERROR "${why}")
endmacro()
execute_process(COMMAND ${EXE} --gtest_list_tests
                OUTPUT_VARIABLE listing ERROR_VARIABLE errors RESULT_VARIABLE rc TIMEOUT 60)
if(NOT rc EQUAL 0)
  refuse("${EXE} --gtest_list_tests failed (${rc}):\n${errors}")
endif()
string(REPLACE "\n" ";" lines "${listing}")
set(suites "")
foreach(line IN LISTS lines)
  # A suite line starts in column 0 and ends with '.', e.g. "KnownTransform." or
  # "Formats/ReadsEveryFormat.  # TypeParam = ..."; test lines are indented.
  if(line MATCHES "^([^ #][^ ]*)\\.( |$)")
    list(APPEND suites "${CMAKE_MATCH_1}")
  endif()
endforeach()
list(REMOVE_DUPLICATES suites)
if(NOT suites)
  refuse("${EXE} lists no test suite")
endif()
string(REPLACE "," ";" LABELS "${LABELS}")
set(script "# Written by cmake/GTestSuitesScan.cmake from ${EXE} --gtest_list_tests.\n")
foreach(suite IN LISTS suites)
  # The CTest name: the suite, '/' of a parameterised instance kept ("Formats/ReadsEveryFormat").
  string(APPEND script "add_test([==[${suite}]==] [==[${EXE}]==] [==[--gtest_filter=${suite}.*]==])\n"
                       "set_tests_properties([==[${suite}]==] PROPERTIES TIMEOUT ${TIMEOUT}")
  if(LABELS)
    string(APPEND script " LABELS [==[${LABELS}]==]")
  endif()
  if(SKIP_REGULAR_EXPRESSION)
    string(APPEND script " SKIP_REGULAR_EXPRESSION [==[${SKIP_REGULAR_EXPRESSION}]==]")
  endif()
  string(APPEND script ")\n")
endforeach()
file(WRITE ${OUT} "${script}")
