# penumbra_embed_shaders(TARGET ROOT dir FILES f...): compiles the shader files into TARGET as a
# table of (path relative to ROOT, source), so installed binaries run from any directory.
function(penumbra_embed_shaders target)
  cmake_parse_arguments(ARG "" "ROOT;NAME" "FILES" ${ARGN})
  set(out ${CMAKE_CURRENT_BINARY_DIR}/${ARG_NAME}.cpp)
  set(inputs)
  foreach(f IN LISTS ARG_FILES)
    list(APPEND inputs ${ARG_ROOT}/${f})
  endforeach()
  add_custom_command(
    OUTPUT ${out}
    COMMAND ${CMAKE_COMMAND} -DROOT=${ARG_ROOT} -DNAME=${ARG_NAME} "-DFILES=${ARG_FILES}" -DOUT=${out}
            -P ${PROJECT_SOURCE_DIR}/cmake/GenerateEmbeddedShaders.cmake
    DEPENDS ${inputs} ${PROJECT_SOURCE_DIR}/cmake/GenerateEmbeddedShaders.cmake
    COMMENT "Embedding shaders into ${ARG_NAME}.cpp"
    VERBATIM)
  target_sources(${target} PRIVATE ${out})
endfunction()
