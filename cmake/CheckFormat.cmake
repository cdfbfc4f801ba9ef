# The formatting check (CTest "format"): every C++ source of the project against the committed
# .clang-format, with clang-format 14 (other versions format differently).
#   cmake -DSOURCE_DIR=<checkout> -DCLANG_FORMAT=<clang-format> -P cmake/CheckFormat.cmake
# The file list is globbed when the test runs, so new files are checked without a reconfigure.
# Fix a failure with: clang-format -i <file>
cmake_minimum_required(VERSION 3.25)

# Files that other branches are rewriting at the time of writing, formatted there. Each entry
# must still exist and still fail the check: once it is formatted (or gone) the check fails
# until it is removed here, so the list can only shrink.
set(pending
)

if(NOT CLANG_FORMAT OR NOT EXISTS "${CLANG_FORMAT}")
  message(FATAL_ERROR "clang-format not found (Debian: clang-format-14)")
endif()
execute_process(COMMAND ${CLANG_FORMAT} --version OUTPUT_VARIABLE version)
if(NOT version MATCHES "clang-format version 14\\.")
  message(FATAL_ERROR "${CLANG_FORMAT} is not clang-format 14: ${version}")
endif()

set(globs)
foreach(dir app modules resampling tests)
  foreach(ext h hpp c cc cpp)
    list(APPEND globs ${SOURCE_DIR}/${dir}/*.${ext})
  endforeach()
endforeach()
file(GLOB_RECURSE files RELATIVE ${SOURCE_DIR} ${globs})
file(GLOB top RELATIVE ${SOURCE_DIR} ${SOURCE_DIR}/*.h ${SOURCE_DIR}/*.cpp)
list(APPEND files ${top})
list(SORT files)

set(problems)
foreach(file IN LISTS pending)
  if(NOT EXISTS ${SOURCE_DIR}/${file})
    list(APPEND problems "${file} is listed as pending in cmake/CheckFormat.cmake but is gone: remove it there")
    continue()
  endif()
  list(REMOVE_ITEM files ${file})
  execute_process(COMMAND ${CLANG_FORMAT} --dry-run --Werror ${file}
                  WORKING_DIRECTORY ${SOURCE_DIR} RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
  if(rc EQUAL 0)
    list(APPEND problems "${file} is formatted now: remove it from the pending list in cmake/CheckFormat.cmake")
  endif()
endforeach()

list(LENGTH files count)
execute_process(COMMAND ${CLANG_FORMAT} --dry-run --Werror ${files}
                WORKING_DIRECTORY ${SOURCE_DIR} RESULT_VARIABLE rc ERROR_VARIABLE diagnostics)
if(NOT rc EQUAL 0)
  string(REGEX MATCHALL "[^\n]+: error: [^\n]+" lines "${diagnostics}")
  set(bad)
  foreach(line IN LISTS lines)
    string(REGEX REPLACE ":[0-9]+:[0-9]+: error:.*" "" file "${line}")
    list(APPEND bad ${file})
  endforeach()
  list(REMOVE_DUPLICATES bad)
  list(JOIN bad "\n  " bad)
  message("${diagnostics}")
  list(APPEND problems "not formatted (clang-format -i):\n  ${bad}")
endif()

if(problems)
  list(JOIN problems "\n" problems)
  message(FATAL_ERROR "${problems}")
endif()
message(STATUS "${count} files formatted as .clang-format says")
