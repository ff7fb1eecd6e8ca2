// The fuzz targets' bodies in the normal test suite (no libFuzzer, no clang needed): every seed
// (tests/fuzz/make-seed-corpora) and every input a fuzzer crashed on (tests/fuzz/regressions/
// <target>/, one file per finding, named after what it broke) goes through the same body the
// fuzzer runs. A body returns for any input; a crash, a sanitizer report (in the --asan build) or
// an exception other than the parsers' own errors fails the test.
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "fuzz_targets.hpp"

namespace {

namespace fs = std::filesystem;

using Body = std::function<void(const std::uint8_t*, std::size_t)>;

const std::map<std::string, Body> kTargets = {
    {"render_request", &lgh::fuzz::renderRequest},
    {"gltf_loader", &lgh::fuzz::gltfLoader},
    {"http_upload", &lgh::fuzz::httpUpload},
    {"texture_decoder", &lgh::fuzz::textureDecoder},
};

std::vector<char> readBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Made once per process, removed at exit.
struct SeedDir {
  fs::path path;
  ~SeedDir() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
};

const fs::path& seedDir() {
  static const SeedDir dir{[] {
    fs::path made = fs::temp_directory_path() / ("lgh-fuzz-seeds-" + std::to_string(::getpid()));
    fs::remove_all(made);
    const std::string command =
        "python3 '" LGH_TEST_DATA_DIR "/fuzz/make-seed-corpora' '" + made.string() + "'";
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
    return made;
  }()};
  return dir.path;
}

std::size_t replay(const std::string& target, const fs::path& dir) {
  if (!fs::is_directory(dir)) return 0;
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.is_regular_file()) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.string());
    const std::vector<char> bytes = readBytes(file);
    kTargets.at(target)(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  }
  return files.size();
}

class FuzzRegressions : public ::testing::TestWithParam<std::string> {
 protected:
  static void SetUpTestSuite() { lgh::fuzz::setUpQuietLogging(); }
};

TEST_P(FuzzRegressions, SeedsAndFindingsPassTheirTarget) {
  const std::string target = GetParam();
  const std::size_t seeds = replay(target, seedDir() / target);
  const std::size_t findings =
      replay(target, fs::path(LGH_TEST_DATA_DIR) / "fuzz" / "regressions" / target);
  EXPECT_GT(seeds, 0U) << "no seeds for " << target;
  std::cout << target << ": " << seeds << " seeds, " << findings << " earlier findings\n";
}

INSTANTIATE_TEST_SUITE_P(Targets, FuzzRegressions,
                         ::testing::Values("render_request", "gltf_loader", "http_upload",
                                           "texture_decoder"));

}  // namespace
