// lghd's glTF loader against the Khronos glTF validator (npm gltf-validator), asset by asset, over
// Debian's assimp glTF2 collection (its broken files included), the hand-made hostile assets of
// tests/gltf_validator/hostile/ and the GLB seeds of the glTF fuzz target. Where the validator
// reports an error, lghd must refuse the asset naming a JSON pointer the validator names (or a
// prefix of it), or load it with a warning that documents a repair the specification allows
// (kRepairs). Where the validator reports none, lghd must load it. The deliberate exceptions are
// kKnownDifferences, each with its reason, mirrored in docs/TESTING.md; a listed asset that stops
// differing fails the test too, so the list stays true.
//
// The validator is installed with npm into <build>/gltf-validator on first use. Without npm or
// without a registry the test skips, saying why, unless LGH_REQUIRE_CROSS_CHECK=1 (set by
// scripts/run-tests), which turns the skip into a failure; so does a run that compared nothing.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "lgh/error.hpp"
#include "scene/gltf/gltf_loader.hpp"
#include "test_support.hpp"

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr const char* kValidatorPackage = "gltf-validator@2.0.0-dev.3.10";

// Validator error codes lghd answers with a repair and a warning instead of a refusal, with the
// warning text that shows the repair was made (any of them).
const std::map<std::string, std::vector<std::string>> kRepairs = {
    // lghd never reads accessor.min/max: bounds come from the data.
    {"ACCESSOR_MIN_MISMATCH", {"min/max"}},
    {"ACCESSOR_MAX_MISMATCH", {"min/max"}},
    {"ACCESSOR_ELEMENT_OUT_OF_MIN_BOUND", {"min/max"}},
    {"ACCESSOR_ELEMENT_OUT_OF_MAX_BOUND", {"min/max"}},
    {"MESH_PRIMITIVE_POSITION_ACCESSOR_WITHOUT_BOUNDS", {"min/max"}},
    // Normals that are not unit length are normalized; zero ones rebuilt from the faces.
    {"ACCESSOR_VECTOR3_NON_UNIT", {"normals not of unit length", "normals replaced"}},
    // KHR_materials_clearcoat's clearcoatNormalTexture without TANGENT: lghd generates MikkTSpace
    // tangents, as the specification lets a client do.
    {"MESH_PRIMITIVE_NO_TANGENT_SPACE", {"clearcoatNormalTexture"}},
};

// Refusals of valid assets that are lghd's choice, by the start of lghd's message
// (docs/TESTING.md).
const std::map<std::string, std::string> kKnownRefusals = {
    {"the asset requires unsupported glTF extension(s)",
     "a required extension lghd does not implement (KHR_technique_webgl, KHR_texture_basisu, "
     "...), named in the 422"},
};

// Assets on which lghd and the validator deliberately differ (docs/TESTING.md).
const std::map<std::string, std::string> kKnownDifferences = {
    {"accessor_component_type_bogus.gltf",
     "lghd names /accessors/0/componentType itself; the validator names the attribute that uses "
     "the accessor"},
    {"accessor_type_bogus.gltf",
     "lghd names /accessors/0/type itself; the validator names the attribute that uses the "
     "accessor"},
    {"extras_100_deep.gltf",
     "JSON nested 100 levels: over lghd's limit of 64 (413), which keeps recursion bounded"},
    {"node_chain_70_deep.gltf",
     "node hierarchy 71 levels deep: over lghd's limit of 64 (422), which bounds its traversal"},
    {"image_absurd_size.gltf",
     "a PNG header claiming 100000 x 100000 pixels: over --max-texture-size (413) before any "
     "decoding; the validator does not check what the image header claims"},
    {"buffer_without_uri.gltf",
     "a .gltf buffer without uri: lghd has nowhere to read it from (422); the validator leaves "
     "such buffers to the application"},
    {"sparse_indices_float.gltf",
     "sparse indices of FLOAT: the schema allows only unsigned integer types (422); the "
     "validator does not report it"},
};

struct Issue {
  std::string code;
  std::string pointer;
};

struct ValidatorReport {
  std::vector<Issue> errors;
  bool failed = false;  // the validator itself could not validate the file
};

std::string shell(const std::string& command, int& status) {
  std::string output;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) {
    status = -1;
    return output;
  }
  char buffer[4096];
  std::size_t count = 0;
  while ((count = std::fread(buffer, 1, sizeof(buffer), pipe)) > 0) output.append(buffer, count);
  status = pclose(pipe);
  return output;
}

std::string quoted(const std::string& text) { return "'" + text + "'"; }

bool crossCheckRequired() {
  const char* value = std::getenv("LGH_REQUIRE_CROSS_CHECK");
  return value != nullptr && std::string(value) == "1";
}

// Installs the validator into `dir` unless it is there; returns why not on failure.
std::string installValidator(const fs::path& dir) {
  if (fs::exists(dir / "node_modules" / "gltf-validator" / "package.json")) return {};
  int status = 0;
  const std::string node = shell("node --version", status);
  if (status != 0) return "node is not installed: " + node;
  fs::create_directories(dir);
  const std::string output = shell(
      "timeout 180 npm install --prefix " + quoted(dir.string()) +
          " --no-audit --no-fund --fetch-retries=1 --fetch-timeout=30000 " + kValidatorPackage,
      status);
  if (status != 0) return "npm could not install " + std::string(kValidatorPackage) + ": " + output;
  return {};
}

std::vector<fs::path> corpus() {
  std::vector<fs::path> files;
  // The fuzz seeds' GLBs too (the .gltf seeds carry their side files in the fuzzers' own
  // container): compressed_features.glb holds what assimp's set lacks (meshopt, WebP, material
  // layers and variants, lines and points beside triangles).
  for (const fs::path& dir :
       {lgh::test::assimpGltfDir(), fs::path(LGH_TEST_DATA_DIR) / "gltf_validator" / "hostile",
        fs::path(LGH_TEST_DATA_DIR) / "fuzz" / "seeds" / "gltf"}) {
    if (!fs::is_directory(dir)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
      const fs::path& path = entry.path();
      const bool seed = dir.filename() == "gltf";
      if (entry.is_regular_file() &&
          ((path.extension() == ".gltf" && !seed) || path.extension() == ".glb")) {
        files.push_back(path);
      }
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::map<std::string, ValidatorReport> runValidator(const fs::path& validatorDir,
                                                    const std::vector<fs::path>& files) {
  std::string command =
      "node " + quoted((fs::path(LGH_TEST_DATA_DIR) / "gltf_validator" / "validate.mjs").string()) +
      " " + quoted(validatorDir.string());
  for (const fs::path& file : files) command += " " + quoted(file.string());
  int status = 0;
  const std::string output = shell(command, status);
  std::map<std::string, ValidatorReport> reports;
  if (status != 0) {
    ADD_FAILURE() << "the validator script failed: " << output;
    return reports;
  }
  for (const json& entry : json::parse(output.substr(output.find('[')))) {
    ValidatorReport& report = reports[entry["file"].get<std::string>()];
    for (const json& error : entry["errors"]) {
      if (error["code"] == "VALIDATOR_FAILED") report.failed = true;
      report.errors.push_back({error["code"], error["pointer"]});
    }
  }
  return reports;
}

// The name kKnownDifferences uses: relative to the assimp folder, or the hostile file's name.
std::string displayName(const fs::path& file) {
  const std::string text = file.string();
  const std::string assimp = lgh::test::assimpGltfDir().string() + "/";
  return text.starts_with(assimp) ? text.substr(assimp.size()) : file.filename().string();
}

struct LghVerdict {
  bool loaded = false;
  std::string message;
  lgh::ErrorCode code = lgh::ErrorCode::Internal;
  std::vector<std::string> warnings;
};

LghVerdict loadWithLghd(const fs::path& file) {
  LghVerdict verdict;
  try {
    const lgh::Scene scene = lgh::loadGltfFile(file.parent_path(), file.filename().string());
    verdict.loaded = true;
    verdict.warnings = scene.warnings;
  } catch (const lgh::Error& error) {
    verdict.message = error.message();
    verdict.code = error.code();
  }
  return verdict;
}

// Whether `message` names `pointer` or one of its prefixes of two or more tokens
// ("/accessors/0" for "/accessors/0/byteOffset"), as a whole pointer ("/accessors/1" does not
// name "/accessors/10").
bool namesPointer(const std::string& message, const std::string& pointer) {
  std::vector<std::string> candidates{pointer};
  for (std::string prefix = pointer;;) {
    const std::size_t slash = prefix.rfind('/');
    if (slash == std::string::npos || slash == 0) break;
    prefix.resize(slash);
    if (std::count(prefix.begin(), prefix.end(), '/') < 2) break;
    candidates.push_back(prefix);
  }
  for (const std::string& candidate : candidates) {
    for (std::size_t at = message.find(candidate); at != std::string::npos;
         at = message.find(candidate, at + 1)) {
      const std::size_t after = at + candidate.size();
      if (after == message.size() ||
          std::isalnum(static_cast<unsigned char>(message[after])) == 0) {
        return true;
      }
    }
  }
  return false;
}

bool refusalNamesAnIssue(const LghVerdict& lghd, const ValidatorReport& report) {
  bool anyPointer = false;
  for (const Issue& issue : report.errors) {
    if (issue.pointer.empty() || issue.code == "IO_ERROR") continue;
    anyPointer = true;
    if (namesPointer(lghd.message, issue.pointer)) return true;
  }
  return !anyPointer;  // container (GLB) and file errors have no pointer to name
}

// Empty when the validator's errors are all repairs lghd made and said so; else what is missing.
std::string missingRepairs(const LghVerdict& lghd, const ValidatorReport& report) {
  std::string missing;
  for (const Issue& issue : report.errors) {
    const auto repair = kRepairs.find(issue.code);
    bool shown = false;
    if (repair != kRepairs.end()) {
      for (const std::string& evidence : repair->second) {
        for (const std::string& warning : lghd.warnings) {
          shown = shown || warning.find(evidence) != std::string::npos;
        }
      }
    }
    if (!shown) missing += " " + issue.code + " at " + issue.pointer + ";";
  }
  return missing;
}

std::string codesOf(const ValidatorReport& report) {
  std::set<std::string> codes;
  for (const Issue& issue : report.errors) codes.insert(issue.code);
  std::string text;
  for (const std::string& code : codes) text += (text.empty() ? "" : ",") + code;
  return text.empty() ? "valid" : text;
}

TEST(GltfValidatorAgreement, LghdAgreesWithTheKhronosValidator) {
  const fs::path validatorDir = fs::path(LGH_BUILD_DIR) / "gltf-validator";
  if (const std::string why = installValidator(validatorDir); !why.empty()) {
    if (crossCheckRequired()) FAIL() << "LGH_REQUIRE_CROSS_CHECK=1, but " << why;
    GTEST_SKIP() << "the Khronos validator is unavailable, so nothing was compared: " << why;
  }
  const std::vector<fs::path> files = corpus();
  const std::map<std::string, ValidatorReport> reports = runValidator(validatorDir, files);
  std::size_t compared = 0;
  std::set<std::string> stillDiffering;
  std::ostringstream table;
  for (const fs::path& file : files) {
    const auto found = reports.find(file.string());
    if (found == reports.end() || found->second.failed) {
      table << displayName(file) << ": the validator could not validate it; not compared\n";
      continue;
    }
    const ValidatorReport& report = found->second;
    const LghVerdict lghd = loadWithLghd(file);
    const std::string name = displayName(file);
    table << name << ": validator " << codesOf(report) << "; lghd "
          << (lghd.loaded ? "loads" : lgh::errorCodeName(lghd.code) + (": " + lghd.message))
          << "\n";
    ++compared;
    std::string disagreement;
    const bool knownRefusal =
        !lghd.loaded &&
        std::any_of(kKnownRefusals.begin(), kKnownRefusals.end(),
                    [&](const auto& refusal) { return lghd.message.starts_with(refusal.first); });
    if (report.errors.empty() && !lghd.loaded && !knownRefusal) {
      disagreement = "valid for the validator, refused by lghd: " + lghd.message;
    } else if (!report.errors.empty() && lghd.loaded) {
      if (const std::string missing = missingRepairs(lghd, report); !missing.empty()) {
        disagreement =
            "errors for the validator, loaded by lghd without a repair warning for" + missing;
      }
    } else if (!report.errors.empty() && !refusalNamesAnIssue(lghd, report)) {
      disagreement =
          "refused by both, but lghd names none of the validator's pointers: " + lghd.message +
          " (validator: " + report.errors.front().pointer + ")";
    }
    if (kKnownDifferences.count(name) != 0) {
      if (disagreement.empty()) stillDiffering.insert(name);
      continue;
    }
    EXPECT_TRUE(disagreement.empty()) << name << ": " << disagreement;
  }
  for (const std::string& name : stillDiffering) {
    ADD_FAILURE() << name << " is listed in kKnownDifferences (and docs/TESTING.md) but lghd and "
                  << "the validator now agree on it: remove it from both";
  }
  std::cout << table.str();
  if (compared == 0 && crossCheckRequired()) FAIL() << "the cross-check compared no asset";
  EXPECT_GE(compared, 100U) << "the corpus shrank: is assimp-testmodels installed?";
}

}  // namespace
