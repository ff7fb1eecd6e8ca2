# lgh_embed_files(TARGET target NAMESPACE ns FUNCTION fn BASE_DIR dir GLOBS pattern...)
function(lgh_embed_files)
  cmake_parse_arguments(ARG "" "TARGET;NAMESPACE;FUNCTION;BASE_DIR" "GLOBS" ${ARGN})
  file(GLOB_RECURSE files CONFIGURE_DEPENDS ${ARG_GLOBS})
  set(output "${CMAKE_CURRENT_BINARY_DIR}/embedded_${ARG_FUNCTION}.cpp")
  add_custom_command(
    OUTPUT "${output}"
    COMMAND ${CMAKE_COMMAND} -DOUTPUT=${output} -DNAMESPACE=${ARG_NAMESPACE}
            -DFUNCTION=${ARG_FUNCTION} -DBASE_DIR=${ARG_BASE_DIR} "-DFILES=${files}"
            -P ${PROJECT_SOURCE_DIR}/cmake/EmbedFiles.cmake
    DEPENDS ${files} ${PROJECT_SOURCE_DIR}/cmake/EmbedFiles.cmake
    COMMENT "Embedding ${ARG_FUNCTION}"
    VERBATIM)
  target_sources(${ARG_TARGET} PRIVATE "${output}")
endfunction()
