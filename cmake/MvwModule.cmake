# A module's dependencies on other mvw modules, declared once in its folder's mvw.module (as
# VTK's vtk.module does) and read here into the target's target_link_libraries.
#
#   # comment lines
#   NAME
#     study                  the folder's name: modules/study, resampling, app
#   DEPENDS
#     core                   public: its public headers include these, so consumers get them
#     config
#   PRIVATE_DEPENDS
#     io                     private: only its .cpp files (and private headers) include these
#   TEST_DEPENDS
#     dicomout               its tests (tests/<name>/) only: what they check the module against
#
# Each name is a module folder (mvw::<name>). The lists are in link order. TEST_DEPENDS (as in
# VTK's vtk.module) lets a test that needs a higher module to check a class (study's colour
# tables for io's palettes) sit beside that class: mvw_module_tests (tests/CMakeLists.txt) links
# them into the module's test executable; the library never sees them. A module declares
# every module whose headers its code includes, directly, not through another's DEPENDS;
# scripts/module-graph --check (CTest module_deps) checks that against the #includes, that the
# declarations have no cycle and that docs/design.md's dependency picture is theirs.
#
#   mvw_module_link(mvw_study PUBLIC nlohmann_json::nlohmann_json PRIVATE OpenSSL::Crypto)
#
# links the target with PUBLIC mvw::<DEPENDS>... <PUBLIC items> PRIVATE mvw::<PRIVATE_DEPENDS>...
# mvw::warnings mvw::sanitizers <PRIVATE items>. Third-party packages stay in the CMakeLists as
# these items: they come as generator expressions, ${CMAKE_DL_LIBS}, targets of the folder itself
# (mvw_glad) or headers only (libcurl), each with the reason beside it, and find_package()
# (with cmake/mvwConfig.cmake.in) is where they are declared once.
include_guard(GLOBAL)

# Reads <folder>/mvw.module into <prefix>_NAME, <prefix>_DEPENDS, <prefix>_PRIVATE_DEPENDS and
# <prefix>_TEST_DEPENDS.
function(mvw_read_module_file file prefix)
  if(NOT EXISTS ${file})
    message(FATAL_ERROR "${file} is missing: every module folder declares its dependencies there (cmake/MvwModule.cmake)")
  endif()
  file(STRINGS ${file} lines)
  set(section "")
  foreach(keyword NAME DEPENDS PRIVATE_DEPENDS TEST_DEPENDS)
    set(${keyword} "")
  endforeach()
  foreach(line IN LISTS lines)
    string(REGEX REPLACE "#.*" "" line "${line}")
    string(STRIP "${line}" word)
    if(word STREQUAL "")
      continue()
    elseif(word MATCHES "^(NAME|DEPENDS|PRIVATE_DEPENDS|TEST_DEPENDS)$")
      set(section ${word})
    elseif(word MATCHES "^[a-z][a-z0-9_]*$" AND section)
      list(APPEND ${section} ${word})
    else()
      message(FATAL_ERROR "${file}: '${word}' is neither NAME, DEPENDS, PRIVATE_DEPENDS, TEST_DEPENDS nor a module name under one of them")
    endif()
  endforeach()
  set(${prefix}_NAME "${NAME}" PARENT_SCOPE)
  set(${prefix}_DEPENDS "${DEPENDS}" PARENT_SCOPE)
  set(${prefix}_PRIVATE_DEPENDS "${PRIVATE_DEPENDS}" PARENT_SCOPE)
  set(${prefix}_TEST_DEPENDS "${TEST_DEPENDS}" PARENT_SCOPE)
endfunction()

function(mvw_module_link target)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "" "PUBLIC;PRIVATE")
  if(arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "mvw_module_link(${target}): unexpected ${arg_UNPARSED_ARGUMENTS}")
  endif()
  mvw_read_module_file(${CMAKE_CURRENT_SOURCE_DIR}/mvw.module module)
  get_filename_component(folder ${CMAKE_CURRENT_SOURCE_DIR} NAME)
  if(NOT module_NAME STREQUAL folder)
    message(FATAL_ERROR "${CMAKE_CURRENT_SOURCE_DIR}/mvw.module: NAME is '${module_NAME}', not the folder's name '${folder}'")
  endif()
  list(TRANSFORM module_DEPENDS PREPEND mvw::)
  list(TRANSFORM module_PRIVATE_DEPENDS PREPEND mvw::)
  target_link_libraries(${target}
    PUBLIC ${module_DEPENDS} ${arg_PUBLIC}
    PRIVATE ${module_PRIVATE_DEPENDS} mvw::warnings mvw::sanitizers ${arg_PRIVATE})
  # What links mvw_io runs its decoder helper (modules/io/CMakeLists.txt): building it builds
  # the helper.
  if(TARGET mvw_decoder AND ("mvw::io" IN_LIST module_DEPENDS OR "mvw::io" IN_LIST module_PRIVATE_DEPENDS))
    add_dependencies(${target} mvw_decoder)
  endif()
endfunction()
