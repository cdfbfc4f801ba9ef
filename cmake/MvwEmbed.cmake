# Text files compiled into a library, keyed by their path relative to a folder (the shaders, the
# validation report template), so the binary needs no resource files at run time:
#
#   mvw_embed_files(target DIR <folder> GLOB <pattern> HEADER <header> NAMESPACE <ns>
#                   FUNCTION <name>)
#
# adds a generated source to `target` defining
#   const std::map<std::string_view, std::string_view>& <ns>::<name>()
# (declared in <header>), regenerated when a matching file or cmake/EmbedFiles.cmake changes.
include_guard(GLOBAL)

function(mvw_embed_files target)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "DIR;GLOB;HEADER;NAMESPACE;FUNCTION" "")
  file(GLOB_RECURSE inputs CONFIGURE_DEPENDS ${arg_DIR}/${arg_GLOB})
  set(script ${PROJECT_SOURCE_DIR}/cmake/EmbedFiles.cmake)
  set(output ${CMAKE_CURRENT_BINARY_DIR}/${arg_FUNCTION}.cpp)
  add_custom_command(
    OUTPUT ${output}
    COMMAND ${CMAKE_COMMAND} -DDIR=${arg_DIR} -DGLOB=${arg_GLOB} -DOUTPUT=${output}
            -DHEADER=${arg_HEADER} -DNAMESPACE=${arg_NAMESPACE} -DFUNCTION=${arg_FUNCTION}
            -P ${script}
    DEPENDS ${inputs} ${script}
    COMMENT "Embedding ${arg_DIR}/${arg_GLOB}"
    VERBATIM)
  target_sources(${target} PRIVATE ${output})
endfunction()
