// Binding, dispatch and work-group slots shared by the C++ passes and the shaders, as Falcor's
// HostDeviceShared headers: plain #defines, valid GLSL and valid C++. The shaders include this
// file; C++ includes it through renderer/src/gl/slots.hpp. Change a number here and both follow.
//   LGH_BIND_*   shader storage buffer bindings     LGH_IMAGE_*  image units
//   LGH_UNIT_*   texture units                      LGH_SLOT_*   dispatch-indirect slots
#ifndef LGH_SLOTS_GLSL
#define LGH_SLOTS_GLSL

// ---- a frame's passes ---------------------------------------------------------------------------
// Texture units 0..4 hold the G-buffer (include/gbuffer.glsl); a pass's own input texture (the
// tile atlas, the tile depth, the shadow ratio being filtered) comes after them.
#define LGH_UNIT_PASS_INPUT 5
#define LGH_BIND_LIGHTS 0           // analytic lights (include/lights.glsl)
#define LGH_BIND_RAY_ORIGINS 6      // shadow rays: vec4 origin per pixel
#define LGH_BIND_RAY_TARGETS 7      // shadow rays: vec4 target per pixel and ray
#define LGH_BIND_RAY_VISIBILITY 8   // shadow rays: visibility bits, uint per pixel and word
#define LGH_IMAGE_SHADOW_RATIO 0    // the shadow ratio a filter pass writes
#define LGH_UNIT_COMPOSITE_RATIO 3  // the filtered shadow ratio in composite.comp
#define LGH_UNIT_GBUFFER_LAYERS 6   // the G-buffer's material layers (include/gbuffer.glsl)

// ---- the LGH lighting passes (include/lgh_shading.glsl) -----------------------------------------
#define LGH_BIND_GRID_LIGHTS 0
#define LGH_BIND_LEVELS 1
#define LGH_BIND_SAMPLES 2  // k shadow samples per pixel; the shadow passes read them here too
#define LGH_BIND_POINT_LIGHTS 3
#define LGH_BIND_TILE_DRAWS 4
#define LGH_IMAGE_RESERVOIR_SUM 0
#define LGH_IMAGE_LOCK 1
#define LGH_IMAGE_OVERDRAW 2
#define LGH_IMAGE_OUTPUT 3

// ---- global illumination: light paths and the path-traced reference (docs/GI.md) ----------------
// Their own programs; texture units 0..4 stay the G-buffer (the reference reads it).
#define LGH_BIND_GI_RAYS 0        // closest-hit batch: 2 x vec4 per ray (vk/shadow_tracer.hpp)
#define LGH_BIND_GI_HITS 1        // closest-hit batch: HitRecord per ray (include/hit_record.glsl)
#define LGH_BIND_GI_VERTICES 2    // the scene's triangles (include/hit_surface.glsl)
#define LGH_BIND_GI_INDICES 3
#define LGH_BIND_GI_GEOMETRIES 4
#define LGH_BIND_GI_INSTANCES 5
#define LGH_BIND_GI_MATERIALS 6   // GiMaterial per material (include/gi_material.glsl)
#define LGH_BIND_GI_SOURCES 7     // GiSource per light source (include/gi_sources.glsl)
#define LGH_BIND_GI_PATHS 8       // per light path or camera path: its state
#define LGH_BIND_GI_VPLS 9        // PointLight per VPL slot (the LGH build's input)
#define LGH_BIND_GI_LIGHTS 10     // the frame's analytic lights (include/lights.glsl)
#define LGH_BIND_GI_RADIANCE 11   // the reference's accumulated radiance, vec4 per pixel
#define LGH_UNIT_GI_ALBEDO 6      // base-colour textures, downsampled into one array
#define LGH_BIND_GI_ALBEDO_TEXELS 12  // Vulkan's light paths: the same array as texels (gi_material.glsl)

// ---- the LGH build (include/lgh_types.glsl, LGH_BUILD_INTERNALS) --------------------------------
#define LGH_BIND_BUILD_LIGHTS 0
#define LGH_BIND_BUILD_LEVELS 1
#define LGH_BIND_BUILD_STATE 2
#define LGH_BIND_BUILD_PARTIALS 3
#define LGH_BIND_BUILD_ACCUM 4
#define LGH_BIND_BUILD_GRID_LIGHTS 5
#define LGH_BIND_BUILD_RECORDS 6  // also the binned S1's lights, written before the records
#define LGH_BIND_BUILD_RANK 7
#define LGH_BIND_BUILD_BITMAPS 8
#define LGH_BIND_BUILD_BLOCKS 9
#define LGH_BIND_BUILD_DRAWS 10
#define LGH_BIND_BUILD_TOUCHED 11
#define LGH_BIND_BUILD_BIN_COUNT 12
#define LGH_BIND_BUILD_BIN_START 13
#define LGH_BIND_BUILD_BIN_ITEMS 14

// Sizes the build's kernels and its C++ side (renderer/src/lightgrid/lgh_builder.cpp) share.
#define LGH_BOUNDS_ITEMS 8          // lights per thread in the bounds reduction
#define LGH_BLOCK 1024              // dense vertices per compaction block (4 per thread)
#define LGH_PYRAMID_STEPS 3u        // at most this many pyramid dispatches (more is left to the tail)
// Binned S1 (lgh_bin_*.comp): tiles of T^3 S1 cells, accumulated in shared memory over their
// (T+1)^3 vertices by one work group per chunk of LGH_BIN_CHUNK lights. T per atomics mode, so
// that the tile's accumulators stay under 32 KB (the GL minimum of shared memory): 9 floats x 9^3
// = 26.2 KB, 9 x 2 words x 7^3 = 24.7 KB.
#define LGH_BIN_TILE_FLOAT 8u
#define LGH_BIN_TILE_FIXED 6u
#define LGH_BIN_CHUNK 1024u

// Dispatch-indirect slots of the build (uvec4: xyz = work groups, w = items, read by the kernel).
#define LGH_SLOT_PYRAMID 0  // + step (0..2)
#define LGH_SLOT_COMPACT_S1 6
#define LGH_SLOT_COMPACT_REST 7
#define LGH_SLOT_COMPACT_ALL 8
#define LGH_SLOT_GATHER_ALL 9
#define LGH_SLOT_GATHER 8    // + level (2..16): 10..24
#define LGH_SLOT_SCATTER 24  // + level (1..16): 25..40
#define LGH_SLOT_BIN_ACCUM 41  // binned S1: one group per (tile, chunk) work item
#define LGH_DISPATCH_SLOTS 42

// ---- output packing (passes/pixel_pack_pass.hpp) --------------------------------------------------
#define LGH_BIND_PACKED_PIXELS 0  // the frame's pixel-pack buffer, as uint words
#define LGH_PACK_GROUP 256        // invocations per work group (a word, or four pixels, each)

// ---- work groups --------------------------------------------------------------------------------
#define LGH_GROUP_2D 8  // 8 x 8 invocations for per-pixel compute passes
#define LGH_GROUP 256   // the build's 1D kernels

#endif
