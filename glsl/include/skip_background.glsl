// Lets a per-pixel compute pass skip its work where a whole SIMD group of invocations shows
// background. Include it first: its #extension line must come before any declaration.
//
// On a CPU rasteriser (llvmpipe) an invocation group is one SIMD vector, and a branch on a
// per-pixel condition is no branch at all: both sides run for every lane under a mask, so a
// background pixel paid for the whole lighting of a surface. A vote over the group is the same
// for all its lanes, which llvmpipe compiles to a real branch: groups of background pixels jump
// over the work (docs/BENCHMARKS.md). On a GPU the vote is the warp's branch it takes anyway.
#ifndef LGH_SKIP_BACKGROUND_GLSL
#define LGH_SKIP_BACKGROUND_GLSL

#extension GL_ARB_shader_group_vote : enable

// Whether any active invocation of this one's group has `covered` set. Without the extension,
// this invocation's own value: the caller's branch is then per pixel, with the same result.
bool anyInvocationCovers(bool covered) {
#ifdef GL_ARB_shader_group_vote
  return anyInvocationARB(covered);
#else
  return covered;
#endif
}

#endif
