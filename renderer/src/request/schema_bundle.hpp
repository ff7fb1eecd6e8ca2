// Turns a proto schema and the files it references into one self-contained document that
// valijson can compile without fetching anything.
//
// The proto files are JSON Schema 2020-12; valijson 1.0 knows draft 7. They are written in the
// forms both read the same way: "$defs" is only a place that "$ref" pointers lead to, and a
// "$ref" has no siblings but annotations (valijson ignores siblings of "$ref", as draft 7 did).
// One keyword needs help: OpenAPI's "discriminator" beside a "oneOf" (the camera). valijson would
// try every branch of the oneOf and report each one's errors; the bundle lowers it to one
// "if"/"then" per discriminator value, which accepts the same documents (every branch has its
// own constant discriminator value) and reports only the errors of the branch the value selects.
//
// Why not valijson's fetchDoc callback: valijson 1.0 ignores "$id", and its schema cache keys
// fetched documents by the referencing document's scope plus the JSON Pointer, so "#/$defs/vec3"
// in two files collide. Bundling gives every node a unique pointer.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace lgh {

// `rootFile` (e.g. "render-request.schema.json") with every file it references, directly or not,
// copied under "$defs" keyed by file name, every "$ref" rewritten to a local pointer, and every
// discriminated "oneOf" lowered to "if"/"then" (see above).
// A reference's document part is matched by file name (the last path segment), so both
// "camera.schema.json" and "https://lghd.invalid/proto/camera.schema.json" resolve from the
// embedded proto files. Throws lgh::Error(Internal) for a reference to an unknown file or a
// discriminator whose mapping does not match its oneOf.
nlohmann::json bundleSchema(const std::string& rootFile);

}  // namespace lgh
