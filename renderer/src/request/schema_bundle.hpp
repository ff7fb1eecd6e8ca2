// Turns a proto schema and the files it references into one self-contained document that
// valijson can compile without fetching anything.
//
// Why not valijson's fetchDoc callback: valijson 1.0 ignores draft-07 "$id", and its schema cache
// keys fetched documents by the referencing document's scope plus the JSON Pointer, so
// "#/definitions/vec3" in two files collide. Bundling gives every node a unique pointer.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace lgh {

// `rootFile` (e.g. "render-request.schema.json") with every file it references, directly or not,
// copied under "definitions" keyed by file name, and every "$ref" rewritten to a local pointer.
// A reference's document part is matched by file name (the last path segment), so both
// "camera.schema.json" and "https://lghd.invalid/proto/camera.schema.json" resolve from the
// embedded proto files. Throws lgh::Error(Internal) for a reference to an unknown file.
nlohmann::json bundleSchema(const std::string& rootFile);

}  // namespace lgh
