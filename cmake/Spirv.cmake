# lgh_embed_spirv(TARGET target NAMESPACE ns SOURCES shader...)
# Compiles each Vulkan GLSL shader to SPIR-V with glslc at build time (--target-env=vulkan1.2 -O;
# #include dependencies tracked through glslc's depfile; includes found beside the shader, else
# from glsl/ as the GL shaders name them: "include/...") and adds to `target` a generated C++
# source that holds it: `std::span<const std::uint32_t> ns::<file name as a C identifier>()`,
# e.g. shadow_ray.rgen -> ns::shadow_ray_rgen(). The binaries carry their SPIR-V with them.
function(lgh_embed_spirv)
  cmake_parse_arguments(ARG "" "TARGET;NAMESPACE" "SOURCES" ${ARGN})
  find_program(LGH_GLSLC glslc REQUIRED DOC "glslc (Debian: glslc)")
  foreach(source IN LISTS ARG_SOURCES)
    get_filename_component(name "${source}" NAME)
    string(MAKE_C_IDENTIFIER "${name}" symbol)
    set(spirv "${CMAKE_CURRENT_BINARY_DIR}/spirv/${name}.spv")
    set(output "${CMAKE_CURRENT_BINARY_DIR}/spirv/${name}.cpp")
    add_custom_command(
      OUTPUT "${spirv}"
      COMMAND ${LGH_GLSLC} --target-env=vulkan1.2 -O -I ${PROJECT_SOURCE_DIR}/glsl -MD -MF "${spirv}.d" -o "${spirv}" "${source}"
      DEPENDS "${source}"
      DEPFILE "${spirv}.d"
      COMMENT "glslc ${name}"
      VERBATIM)
    add_custom_command(
      OUTPUT "${output}"
      COMMAND ${CMAKE_COMMAND} -DINPUT=${spirv} -DOUTPUT=${output} -DNAMESPACE=${ARG_NAMESPACE}
              -DSYMBOL=${symbol} -DSOURCE=${name} -P ${PROJECT_SOURCE_DIR}/cmake/SpirvToCpp.cmake
      DEPENDS "${spirv}" ${PROJECT_SOURCE_DIR}/cmake/SpirvToCpp.cmake
      COMMENT "Embedding ${name}.spv"
      VERBATIM)
    target_sources(${ARG_TARGET} PRIVATE "${output}")
  endforeach()
endfunction()
