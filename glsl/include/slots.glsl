// Binding and work-group slots shared by the C++ passes and the shaders (as Falcor's
// HostDeviceShared headers): one #define per slot, read by GLSL and, through
// renderer/src/gl/slots.hpp, by C++. Change a number here and both sides follow.
#ifndef LGH_SLOTS_GLSL
#define LGH_SLOTS_GLSL

// ---- frame-level shader storage buffers -------------------------------------------------------
#define LGH_SLOT_LIGHTS 0             // analytic lights (include/lights.glsl)
#define LGH_SLOT_SHADOW_SAMPLES 2     // the LGH's k shadow samples per pixel (== LGH_BINDING_SAMPLES)
#define LGH_SLOT_RAY_ORIGINS 6        // shadow rays: vec4 origin per pixel
#define LGH_SLOT_RAY_TARGETS 7        // shadow rays: vec4 target per pixel and ray
#define LGH_SLOT_RAY_VISIBILITY 8     // shadow rays: visibility bits, uint per pixel and word

// ---- images and textures beyond the G-buffer's units 0..4 -------------------------------------
#define LGH_SLOT_SHADOW_RATIO_IN 5    // sampler: the shadow ratio a pass reads
#define LGH_SLOT_SHADOW_RATIO_OUT 0   // image: the shadow ratio a pass writes
#define LGH_SLOT_COMPOSITE_RATIO 3    // sampler unit of the filtered ratio in composite.frag
#define LGH_SLOT_GBUFFER_LAYERS 6     // sampler: the G-buffer's material layers (include/gbuffer.glsl)

// ---- work groups --------------------------------------------------------------------------------
#define LGH_GROUP_2D 8                // 8 x 8 invocations for per-pixel compute passes

#endif
