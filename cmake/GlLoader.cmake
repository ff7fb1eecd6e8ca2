# lgh_generate_gl_loader(TARGET target)
# Generates the GL and EGL loaders at build time with glad 2 (Debian's python3-glad) from the
# Khronos XML registry it ships, and adds them to `target`:
#   - GL 4.6 core + the extensions the renderer asks for, in glad's multi-context form: one
#     GladGLContext table per context, filled through that context's own proc-address function
#     (eglGetProcAddress, OSMesaGetProcAddress). gl_api_macros.h, generated from the table, maps
#     every glFoo to the table of the context current on the calling thread (src/gl/gl_api.hpp).
#   - EGL 1.5 + the device/platform extensions, with glad's own loader: libEGL.so.1 is opened at
#     run time, so a machine without EGL still starts (and can render through OSMesa).
find_program(GLAD_EXECUTABLE glad REQUIRED)

set(LGH_GL_EXTENSIONS
    GL_ARB_fragment_shader_interlock GL_NV_shader_atomic_float GL_ARB_gl_spirv
    GL_EXT_memory_object GL_EXT_memory_object_fd GL_EXT_semaphore GL_EXT_semaphore_fd
    GL_EXT_texture_filter_anisotropic GL_ARB_texture_filter_anisotropic GL_NVX_gpu_memory_info
    GL_KHR_robustness GL_ARB_robustness GL_EXT_texture_compression_s3tc
    GL_KHR_parallel_shader_compile GL_KHR_debug GL_AMD_pinned_memory)
set(LGH_EGL_EXTENSIONS
    EGL_EXT_device_base EGL_EXT_device_enumeration EGL_EXT_device_query EGL_EXT_platform_base
    EGL_EXT_platform_device EGL_MESA_platform_surfaceless EGL_KHR_surfaceless_context
    EGL_KHR_no_config_context EGL_EXT_device_drm EGL_KHR_get_all_proc_addresses
    EGL_KHR_client_get_all_proc_addresses EGL_KHR_create_context
    EGL_EXT_create_context_robustness)

function(lgh_generate_gl_loader)
  cmake_parse_arguments(ARG "" "TARGET" "" ${ARGN})
  set(out ${CMAKE_CURRENT_BINARY_DIR}/glad)
  list(JOIN LGH_GL_EXTENSIONS "," gl_extensions)
  list(JOIN LGH_EGL_EXTENSIONS "," egl_extensions)
  add_custom_command(
    OUTPUT ${out}/gl/include/glad/gl.h ${out}/gl/src/gl.c
    COMMAND ${GLAD_EXECUTABLE} --quiet --reproducible --api gl:core=4.6
            --extensions ${gl_extensions} --out-path ${out}/gl c --mx
    COMMENT "Generating the GL loader (glad, GL 4.6 core, multi-context)"
    VERBATIM)
  add_custom_command(
    OUTPUT ${out}/egl/include/glad/egl.h ${out}/egl/src/egl.c
    COMMAND ${GLAD_EXECUTABLE} --quiet --reproducible --api egl=1.5
            --extensions ${egl_extensions} --out-path ${out}/egl c --loader
    COMMENT "Generating the EGL loader (glad, EGL 1.5)"
    VERBATIM)
  add_custom_command(
    OUTPUT ${out}/gl/include/gl_api_macros.h
    COMMAND ${CMAKE_COMMAND} -DINPUT=${out}/gl/include/glad/gl.h
            -DOUTPUT=${out}/gl/include/gl_api_macros.h
            -P ${PROJECT_SOURCE_DIR}/cmake/GlApiMacros.cmake
    DEPENDS ${out}/gl/include/glad/gl.h ${PROJECT_SOURCE_DIR}/cmake/GlApiMacros.cmake
    COMMENT "Generating gl_api_macros.h"
    VERBATIM)
  add_custom_target(${ARG_TARGET}_glad DEPENDS ${out}/gl/include/gl_api_macros.h
                                               ${out}/egl/include/glad/egl.h)
  add_dependencies(${ARG_TARGET} ${ARG_TARGET}_glad)
  target_sources(${ARG_TARGET} PRIVATE ${out}/gl/src/gl.c ${out}/egl/src/egl.c)
  # PUBLIC: tests and the internal targets include src/gl/gl_api.hpp too.
  target_include_directories(${ARG_TARGET} SYSTEM PUBLIC ${out}/gl/include ${out}/egl/include)
endfunction()
