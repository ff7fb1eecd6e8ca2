// The atrium: the GI benchmark's scene, built in code (no files), in the spirit of the paper's
// (a long hall with columns, arches and hanging cloth; Lin & Yuksel 2019, Figs. 1, 5-10).
//
// Units are metres, +Y up, the hall runs along Z:
//  - hall: x in [-6, 6], y in [0, 10], z in [-20, 20]; a tiled stone floor (checker texture),
//  plaster
//    side and end walls, a timber ceiling at y = 10 with a skylight slot over the nave
//    (|x| < 1.6) that the sun comes in through;
//  - two colonnades at x = +-3.5: 9 marble columns each (z = -16 .. 16, 4 m apart), radius 0.35,
//    7 m high on square plinths, with semicircular stone arches between them and a wall above up to
//    the ceiling (the clerestory);
//  - three hanging cloths in the nave (red, blue, green; double-sided, draped in folds), hung from
//    bars across it at z = -10, -2, 6 and staggered (x = 0, 1.6, -1.6) so that the view down the
//    nave stays open, and a polished brass rail along each colonnade (the glossy pixels of the
//    error metrics);
//  - over 100K triangles: the columns, arches and cloths are finely tessellated (the paper's
//    figures come from a scene of that size, and its tables from 1K to 1M VPLs on it).
//
// Lights: a warm sun (directional, 6 lux) through the skylight, slanted so that it lights a band
// of the nave's floor (x from -4.6 to -1.4, under and beside the left arcade) and the cloths, and
// two dim lanterns (point, 4 cd) near the far end. The indirect light dominates everywhere the
// sun does not reach directly.
// One camera at (0, 3, 19) looking down the hall (yfov 0.9 rad).
#pragma once

#include "scene/scene.hpp"

namespace lgh {

Scene makeAtriumScene();

}  // namespace lgh
