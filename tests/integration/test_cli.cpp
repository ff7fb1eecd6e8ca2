// The command-line clients as a user runs them: lgh-render and lgh-bench as real processes on
// llvmpipe, checked by exit status, output files and messages.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include <fmt/format.h>

#include "lgh/image.hpp"
#include "test_support.hpp"

namespace lgh::test {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

struct ToolRun {
  int exitCode = -1;
  std::string out;
  std::string err;
};

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Runs build/server/<tool> with `arguments` (already shell-quoted where needed).
ToolRun runTool(const std::string& tool, const std::string& arguments) {
  // ctest runs tests in parallel: every call gets its own capture files.
  static int call = 0;
  const std::string name = fmt::format(
      "{}_{}_{}", ::testing::UnitTest::GetInstance()->current_test_info()->name(), tool, ++call);
  const fs::path dir = outputDir() / "cli";
  fs::create_directories(dir);
  const fs::path out = dir / (name + ".stdout");
  const fs::path err = dir / (name + ".stderr");
  const std::string command = (fs::path(LGH_BUILD_DIR) / "server" / tool).string() + " " +
                              arguments + " >" + out.string() + " 2>" + err.string();
  const int status = std::system(command.c_str());
  ToolRun run;
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.out = slurp(out);
  run.err = slurp(err);
  return run;
}

fs::path outputFile(const std::string& name) {
  fs::path path = outputDir() / "cli" / name;
  fs::create_directories(path.parent_path());
  fs::remove(path);
  return path;
}

image_io::Decoded decodeFile(const fs::path& path) {
  return image_io::decode(image_io::readFile(path), path.string());
}

std::size_t countLines(const std::string& text) {
  std::size_t lines = 0;
  for (const char c : text) lines += c == '\n' ? 1 : 0;
  return lines;
}

TEST(LghRender, DemoWritesThePngTheTimingsAndPrintsTheTable) {
  const fs::path png = outputFile("demo.png");
  const fs::path timings = outputFile("demo_timings.json");
  const ToolRun run =
      runTool("lgh-render", "--demo -o " + png.string() + " --width 40 --height 30" +
                                " --timings " + timings.string());
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const auto image = decodeFile(png);
  EXPECT_EQ(image.width, 40);
  EXPECT_EQ(image.height, 30);
  EXPECT_EQ(image.channels, 3);
  EXPECT_NE(run.out.find("gbuffer"), std::string::npos) << run.out;
  const json summary = json::parse(slurp(timings));
  EXPECT_TRUE(summary.contains("timings")) << summary.dump();
  EXPECT_TRUE(summary.contains("device")) << summary.dump();
}

TEST(LghRender, ExrOutputIsLinearFloat) {
  const fs::path exr = outputFile("demo.exr");
  const ToolRun run =
      runTool("lgh-render", "--demo -q -o " + exr.string() + " --width 16 --height 8");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_TRUE(run.out.empty()) << "--quiet printed: " << run.out;
  const auto image = decodeFile(exr);
  EXPECT_TRUE(image.isFloat);
  EXPECT_EQ(image.width, 16);
}

TEST(LghRender, PngCompressionChangesTheSizeNotThePixels) {
  const fs::path stored = outputFile("level0.png");
  const fs::path smallest = outputFile("level9.png");
  const std::string size = " --width 48 --height 32 -q";
  ASSERT_EQ(runTool("lgh-render", "--demo -o " + stored.string() + size + " --png-compression 0")
                .exitCode,
            0);
  ASSERT_EQ(runTool("lgh-render", "--demo -o " + smallest.string() + size + " --png-compression 9")
                .exitCode,
            0);
  EXPECT_GT(fs::file_size(stored), 48U * 32U * 3U);
  EXPECT_LT(fs::file_size(smallest), fs::file_size(stored));
  EXPECT_EQ(decodeFile(stored).pixels8, decodeFile(smallest).pixels8);
}

TEST(LghRender, ABadRequestFailsWithOneLineNamingTheField) {
  const fs::path request = outputFile("bad_request.json");
  std::ofstream(request) << R"({"output": {"width": -1}})";
  const ToolRun run =
      runTool("lgh-render", request.string() + " -o " + outputFile("x.png").string());
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_EQ(countLines(run.err), 1U) << run.err;
  EXPECT_NE(run.err.find("/output/width"), std::string::npos) << run.err;
}

// The lecture's materials from the CLI: the same request field as the daemon's.
TEST(LghRender, MaterialParametersFromTheRequestFile) {
  const fs::path request = outputFile("materials.json");
  std::ofstream(request) << R"({"output": {"width": 40, "height": 30},
    "materials": [{"match": {"name": "red"}, "parameters": {"model": "oren-nayar", "sigma": 0.6}},
                  {"match": {"all": true}, "parameters": {"sampling": {"filter": "bicubic"}}}]})";
  const fs::path png = outputFile("materials.png");
  const ToolRun run = runTool("lgh-render", request.string() + " -q -o " + png.string());
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(decodeFile(png).width, 40);
  std::ofstream(request) << R"({"materials": [{"match": {"name": "red"},
    "parameters": {"model": "phong", "shininess": -2}}]})";
  const ToolRun bad = runTool("lgh-render", request.string() + " -o " + png.string());
  EXPECT_EQ(bad.exitCode, 1);
  EXPECT_NE(bad.err.find("/materials/0/parameters/shininess"), std::string::npos) << bad.err;
}

TEST(LghRender, MalformedJsonAndMissingFilesNameTheFile) {
  const fs::path malformed = outputFile("malformed.json");
  std::ofstream(malformed) << R"({"output": )";
  const ToolRun broken =
      runTool("lgh-render", malformed.string() + " -o " + outputFile("x.png").string());
  EXPECT_EQ(broken.exitCode, 1);
  EXPECT_NE(broken.err.find("malformed.json"), std::string::npos) << broken.err;
  const ToolRun missing =
      runTool("lgh-render", "/nonexistent/request.json -o " + outputFile("x.png").string());
  EXPECT_EQ(missing.exitCode, 1);
  EXPECT_NE(missing.err.find("/nonexistent/request.json"), std::string::npos) << missing.err;
}

TEST(LghRender, UsageErrorsAreRefusedBeforeRendering) {
  EXPECT_EQ(runTool("lgh-render", "-o x.png").exitCode, 2);
  const ToolRun level = runTool("lgh-render", "--demo -o x.png --png-compression 12");
  EXPECT_NE(level.exitCode, 0);
  EXPECT_NE(level.err.find("png-compression"), std::string::npos) << level.err;
  const ToolRun help = runTool("lgh-render", "--help");
  EXPECT_EQ(help.exitCode, 0);
  EXPECT_NE(help.out.find("--png-compression"), std::string::npos) << help.out;
}

// --- The thumbnailer form: a model in, a PNG out
// ---------------------------------------------------

std::string boxGlb() {
  return (assimpGltfDir() / "BoxTextured-glTF-Binary" / "BoxTextured.glb").string();
}

TEST(LghRenderThumbnail, AModelBecomesASquareThumbnailWithoutAnyJson) {
  const fs::path png = outputFile("thumb_default.png");
  const ToolRun run = runTool("lgh-render", boxGlb() + " -o " + png.string() + " -q");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const auto image = decodeFile(png);
  EXPECT_EQ(image.width, 256);
  EXPECT_EQ(image.height, 256);
  // The model is in the middle of the frame, the background around it.
  const auto at = [&](int x, int y) {
    return image.pixels8[static_cast<std::size_t>((y * image.width + x) * image.channels)];
  };
  EXPECT_NE(at(128, 128), at(2, 2));
}

TEST(LghRenderThumbnail, SizeViewAndTransparency) {
  const fs::path wide = outputFile("thumb_wide.png");
  ASSERT_EQ(runTool("lgh-render", boxGlb() + " -o " + wide.string() + " --size 80x40 -q").exitCode,
            0);
  const auto wideImage = decodeFile(wide);
  EXPECT_EQ(wideImage.width, 80);
  EXPECT_EQ(wideImage.height, 40);

  const fs::path clear = outputFile("thumb_transparent.png");
  const ToolRun transparent =
      runTool("lgh-render", boxGlb() + " -o " + clear.string() + " --size 64 --transparent -q");
  ASSERT_EQ(transparent.exitCode, 0) << transparent.err;
  const auto rgba = decodeFile(clear);
  ASSERT_EQ(rgba.channels, 4);
  EXPECT_EQ(rgba.pixels8[3], 0) << "the corner is background";
  EXPECT_EQ(rgba.pixels8[(32 * 64 + 32) * 4 + 3], 255) << "the centre is the model";

  // Each view looks from its own side: the images differ.
  std::map<std::string, std::vector<std::uint8_t>> views;
  for (const char* view : {"iso", "front", "top", "0.2,1,-1"}) {
    const fs::path file = outputFile(std::string("thumb_view_") + view + ".png");
    const ToolRun run =
        runTool("lgh-render", boxGlb() + " -o " + file.string() + " --size 48 -q --view " + view);
    ASSERT_EQ(run.exitCode, 0) << view << ": " << run.err;
    views[view] = decodeFile(file).pixels8;
  }
  EXPECT_NE(views["iso"], views["front"]);
  EXPECT_NE(views["front"], views["top"]);
  EXPECT_NE(views["top"], views["0.2,1,-1"]);
}

TEST(LghRenderThumbnail, AGltfFindsItsSideFilesBesideIt) {
  const fs::path png = outputFile("thumb_gltf.png");
  const std::string gltf = (assimpGltfDir() / "BoxTextured-glTF" / "BoxTextured.gltf").string();
  const ToolRun run = runTool("lgh-render", gltf + " -o " + png.string() + " --size 32 -q");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(decodeFile(png).width, 32);
}

TEST(LghRenderThumbnail, BadArgumentsAreRefusedWithTheirName) {
  const std::string out = " -o " + outputFile("thumb_bad.png").string();
  const ToolRun view = runTool("lgh-render", boxGlb() + out + " --view diagonal");
  EXPECT_NE(view.exitCode, 0);
  EXPECT_NE(view.err.find("--view"), std::string::npos) << view.err;
  const ToolRun zero = runTool("lgh-render", boxGlb() + out + " --view 0,0,0");
  EXPECT_NE(zero.exitCode, 0);
  const ToolRun size = runTool("lgh-render", boxGlb() + out + " --size 0x10");
  EXPECT_NE(size.exitCode, 0);
  EXPECT_NE(size.err.find("--size"), std::string::npos) << size.err;
  const ToolRun missing = runTool("lgh-render", "/nonexistent/model.glb" + out);
  EXPECT_EQ(missing.exitCode, 1);
  EXPECT_NE(missing.err.find("/nonexistent/model.glb"), std::string::npos) << missing.err;
  const ToolRun viewOfRequest = runTool("lgh-render", "--demo" + out + " --view top");
  EXPECT_EQ(viewOfRequest.exitCode, 2);
  EXPECT_NE(viewOfRequest.err.find("--view"), std::string::npos) << viewOfRequest.err;
  const ToolRun root = runTool("lgh-render", boxGlb() + out + " --asset-root /tmp");
  EXPECT_EQ(root.exitCode, 2);
}

// server/lgh-render.thumbnailer as a desktop file manager runs it: %i the model, %o the PNG to
// write, %s the size.
TEST(LghRenderThumbnail, TheFreedesktopThumbnailerEntryWorksAsWritten) {
  std::ifstream entry(fs::path(LGH_TEST_DATA_DIR) / ".." / "server" / "lgh-render.thumbnailer");
  ASSERT_TRUE(entry);
  std::map<std::string, std::string> keys;
  for (std::string line; std::getline(entry, line);) {
    const std::size_t equals = line.find('=');
    if (equals != std::string::npos) keys[line.substr(0, equals)] = line.substr(equals + 1);
  }
  EXPECT_EQ(keys["TryExec"], "lgh-render");
  EXPECT_NE(keys["MimeType"].find("model/gltf-binary;"), std::string::npos);
  EXPECT_NE(keys["MimeType"].find("model/gltf+json;"), std::string::npos);
  std::string command = keys["Exec"];
  const fs::path png = outputFile("thumbnailer.png");
  for (const auto& [code, value] :
       std::map<std::string, std::string>{{"%i", boxGlb()}, {"%o", png.string()}, {"%s", "128"}}) {
    const std::size_t at = command.find(code);
    ASSERT_NE(at, std::string::npos) << code << " in " << keys["Exec"];
    command.replace(at, code.size(), value);
  }
  const std::string shell = "PATH=" + (fs::path(LGH_BUILD_DIR) / "server").string() + ":$PATH " +
                            command + " 2>" + outputFile("thumbnailer.stderr").string();
  ASSERT_EQ(std::system(shell.c_str()), 0) << shell << "\n"
                                           << slurp(outputDir() / "cli" / "thumbnailer.stderr");
  const auto image = decodeFile(png);
  EXPECT_EQ(image.width, 128);
  EXPECT_EQ(image.height, 128);
  EXPECT_EQ(image.channels, 4);
}

TEST(LghBench, ConstructPrintsJsonRowsForEachCount) {
  const ToolRun run =
      runTool("lgh-bench", "construct --vpls 1000,4000 --iterations 2 --warmup 1 --json");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const json result = json::parse(run.out);
  EXPECT_EQ(result.at("benchmark"), "lgh-construct");
  EXPECT_FALSE(result.at("device").at("image_backend").get<std::string>().empty());
  const json& runs = result.at("runs");
  ASSERT_EQ(runs.size(), 2U) << runs.dump();
  EXPECT_EQ(runs[0].at("vpls"), 1000);
  EXPECT_EQ(runs[1].at("vpls"), 4000);
  for (const json& row : runs) {
    EXPECT_GT(row.at("total_ms").get<double>(), 0.0);
    EXPECT_FALSE(row.at("overflow").get<bool>());
  }
  EXPECT_NE(run.err.find("4000"), std::string::npos) << "the table goes to stderr: " << run.err;
}

}  // namespace
}  // namespace lgh::test
