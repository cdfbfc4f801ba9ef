# Installing a library target into the `mvw` CMake package (mvwConfig.cmake, mvw:: targets).
#
#   mvw_install_library(mvw_study)
#
# Call it once per library, after its target_include_directories(). It
#  - names the exported target after the folder: mvw_study -> mvw::study (the same name as
#    the in-tree alias, so consumers and the tree spell targets alike);
#  - installs the archive into lib/ and the target's public include/ tree (if any) into
#    include/;
#  - keeps the in-tree include paths for the build only ($<BUILD_INTERFACE:...>) and points
#    installed consumers at <prefix>/include;
#  - adds the target to the one export set, mvwTargets, that the top-level CMakeLists writes.
# Static libraries carry their PRIVATE link dependencies into the export as $<LINK_ONLY:...>,
# so a third-party package a library links (even privately) must also be found by
# cmake/mvwConfig.cmake.in (find_dependency), and an in-tree target it links must be
# installed with this function too.
include_guard(GLOBAL)
include(GNUInstallDirs)

function(mvw_install_library)
  foreach(target IN LISTS ARGN)
    if(NOT TARGET ${target})
      message(FATAL_ERROR "mvw_install_library: no target ${target}")
    endif()
    string(REGEX REPLACE "^mvw_" "" export_name ${target})
    set_target_properties(${target} PROPERTIES EXPORT_NAME ${export_name})
    set_property(GLOBAL APPEND PROPERTY MVW_EXPORTED_TARGETS mvw::${export_name})

    # Plain (absolute) include paths point into the source or build tree: build only. The
    # target's own <folder>/include, if public, is installed and replaced by <prefix>/include;
    # so is <build folder>/include, where a generated public header (a version) would go.
    get_target_property(source_dir ${target} SOURCE_DIR)
    get_target_property(binary_dir ${target} BINARY_DIR)
    set(installed_includes "")
    foreach(property INTERFACE_INCLUDE_DIRECTORIES INTERFACE_SYSTEM_INCLUDE_DIRECTORIES)
      get_target_property(dirs ${target} ${property})
      if(NOT dirs)
        continue()
      endif()
      set(wrapped "")
      foreach(dir IN LISTS dirs)
        if(dir MATCHES "^\\$<" OR NOT IS_ABSOLUTE "${dir}")
          list(APPEND wrapped "${dir}")
        else()
          list(APPEND wrapped "$<BUILD_INTERFACE:${dir}>")
          if(dir STREQUAL "${source_dir}/include" OR dir STREQUAL "${binary_dir}/include")
            list(APPEND installed_includes ${dir})
          endif()
        endif()
      endforeach()
      set_property(TARGET ${target} PROPERTY ${property} "${wrapped}")
    endforeach()
    list(REMOVE_DUPLICATES installed_includes)
    foreach(dir IN LISTS installed_includes)
      install(DIRECTORY ${dir}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
    endforeach()
    if(installed_includes)
      target_include_directories(${target} INTERFACE
                                 $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
    endif()
    install(TARGETS ${target} EXPORT mvwTargets
            ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
            LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
            RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  endforeach()
endfunction()
