// config.hpp: lghd's flags and their LGHD_* environment variables. The defaults, good flags in
// the units DaemonConfig keeps, variables (a flag on the command line wins), and bad command lines:
// exit status 2 and a message that names the flag and the value.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "config.hpp"
#include "version.hpp"

extern char** environ;

namespace lghd {
namespace {

// Runs parseConfig on `lghd ARGS...`, keeping what it printed.
struct Parsed {
  ParsedConfig result;
  std::string out;
  std::string err;
};

Parsed parse(std::vector<std::string> args) {
  args.insert(args.begin(), "lghd");
  std::vector<char*> argv;
  argv.reserve(args.size() + 1);
  for (std::string& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  Parsed parsed{parseConfig(static_cast<int>(args.size()), argv.data()), "", ""};
  parsed.out = testing::internal::GetCapturedStdout();
  parsed.err = testing::internal::GetCapturedStderr();
  return parsed;
}

// Every test starts without LGHD_* variables (the runner's environment must not leak in) and
// puts back what it found.
class DaemonConfigTest : public testing::Test {
 protected:
  void SetUp() override {
    for (char** entry = environ; *entry != nullptr; ++entry) {
      const std::string text = *entry;
      if (!text.starts_with("LGHD_")) continue;
      const std::size_t equals = text.find('=');
      saved_.emplace_back(text.substr(0, equals), text.substr(equals + 1));
    }
    for (const auto& [name, value] : saved_) unsetenv(name.c_str());
  }
  void TearDown() override {
    for (const std::string& name : set_) unsetenv(name.c_str());
    for (const auto& [name, value] : saved_) setenv(name.c_str(), value.c_str(), 1);
  }
  void setEnv(const std::string& name, const std::string& value) {
    setenv(name.c_str(), value.c_str(), 1);
    set_.push_back(name);
  }
  // A file in the test's temporary folder holding `text`.
  static std::string writeFile(const std::string& name, const std::string& text) {
    const std::filesystem::path path = std::filesystem::path(testing::TempDir()) / name;
    std::ofstream(path, std::ios::binary) << text;
    return path.string();
  }

 private:
  std::vector<std::pair<std::string, std::string>> saved_;
  std::vector<std::string> set_;
};

TEST_F(DaemonConfigTest, Defaults) {
  const Parsed parsed = parse({});
  ASSERT_TRUE(parsed.result.config) << parsed.err;
  EXPECT_EQ(parsed.result.exitCode, 0);
  EXPECT_EQ(parsed.err, "");
  const DaemonConfig& config = *parsed.result.config;
  EXPECT_EQ(config.host, "127.0.0.1");
  EXPECT_EQ(config.port, 8080);
  EXPECT_EQ(config.httpThreads, 32);
  EXPECT_EQ(config.authToken, "");
  EXPECT_EQ(config.queueDepth, 16);
  EXPECT_EQ(config.deadline, std::chrono::milliseconds(30'000));
  EXPECT_EQ(config.grace, std::chrono::milliseconds(10'000));
  EXPECT_EQ(config.watchdog, std::chrono::milliseconds(60'000));
  EXPECT_EQ(config.sceneCacheBytes, 512ULL << 20);
  EXPECT_EQ(config.logFormat, "json");
  EXPECT_EQ(config.testRenderDelay, std::chrono::milliseconds(0));
  EXPECT_EQ(config.limits.maxBodyBytes, 64ULL << 20);
  EXPECT_EQ(config.limits.maxWidth, 4096);
  EXPECT_EQ(config.limits.maxHeight, 4096);
  EXPECT_EQ(config.limits.maxPixels, 4096LL * 4096LL);
  EXPECT_EQ(config.limits.maxLights, 4096);
  EXPECT_EQ(config.limits.maxVpls, 1 << 20);
  EXPECT_EQ(config.limits.maxTriangles, 5'000'000U);
  EXPECT_EQ(config.limits.maxTextureSize, 8192);
  EXPECT_EQ(config.limits.maxBatch, 64);
  EXPECT_EQ(config.context.backend, "auto");
  EXPECT_EQ(config.context.gpu, 0);
  EXPECT_FALSE(config.context.requireGpu);
  EXPECT_FALSE(config.context.glDebug);
  EXPECT_EQ(config.context.assetRoot, ".");
  EXPECT_EQ(config.context.logLevel, "info") << "the daemon logs more than the CLI tools (warn)";
}

TEST_F(DaemonConfigTest, DefaultsReachTheRendererAndTheRequestLimits) {
  const Parsed parsed = parse({});
  ASSERT_TRUE(parsed.result.config) << parsed.err;
  const lgh::RendererOptions renderer = parsed.result.config->rendererOptions();
  EXPECT_EQ(renderer.backend, lgh::ContextBackend::Auto);
  EXPECT_EQ(renderer.gpuIndex, 0);
  EXPECT_EQ(renderer.assetRoot, std::filesystem::path("."));
  EXPECT_EQ(renderer.maxTriangles, 5'000'000U);
  EXPECT_EQ(renderer.maxTextureSize, 8192);
  EXPECT_EQ(renderer.sceneCacheBytes, 512ULL << 20);
  EXPECT_EQ(renderer.maxTextureBytes, 2048ULL << 20);
  // Untrusted assets are parsed in a worker: this very executable, in worker mode.
  EXPECT_EQ(renderer.sceneWorker.executable, std::filesystem::read_symlink("/proc/self/exe"));
  EXPECT_EQ(renderer.sceneWorker.arguments, std::vector<std::string>{kSceneWorkerFlag});
  EXPECT_EQ(renderer.sceneWorker.memoryBytes, 4096ULL << 20);
  EXPECT_EQ(renderer.sceneWorker.timeoutSeconds, 120.0);
  EXPECT_EQ(parsed.result.config->metricsPort, -1);
  const lgh::RequestLimits limits = parsed.result.config->requestLimits();
  EXPECT_EQ(limits.maxWidth, 4096);
  EXPECT_EQ(limits.maxHeight, 4096);
  EXPECT_EQ(limits.maxPixels, 4096LL * 4096LL);
  EXPECT_EQ(limits.maxLights, 4096);
  EXPECT_EQ(limits.maxVpls, 1 << 20);
  EXPECT_EQ(limits.maxInlineGlbBytes, 64ULL << 20) << "an inline GLB may fill the whole body";
}

TEST_F(DaemonConfigTest, GoodFlagsInDaemonUnits) {
  const std::vector<std::pair<std::string, std::string>> flags{
      {"--host", "0.0.0.0"},
      {"--port", "0"},
      {"--http-threads", "4"},
      {"--auth-token", "s3cret"},
      {"--grace-seconds", "0"},
      {"--watchdog-seconds", "1.5"},
      {"--log-format", "text"},
      {"--queue-depth", "3"},
      {"--deadline-seconds", "2.5"},
      {"--scene-cache-mb", "64"},
      {"--test-render-delay-ms", "25"},
      {"--max-body-mb", "2"},
      {"--max-width", "800"},
      {"--max-height", "600"},
      {"--max-pixels", "480000"},
      {"--max-lights", "10"},
      {"--max-vpls", "1000"},
      {"--max-triangles", "12345"},
      {"--max-texture-size", "1024"},
      {"--max-batch", "5"},
      {"--max-texture-mb", "100"},
      {"--metrics-port", "9090"},
      {"--scene-worker-memory-mb", "512"},
      {"--scene-worker-timeout-seconds", "2.5"},
      {"--test-scene-worker-crash-marker", "boom"},
      {"--backend", "surfaceless"},
      {"--gpu", "1"},
      {"--asset-root", "/srv/assets"},
      {"--log-level", "debug"},
  };
  std::vector<std::string> args{"--require-gpu", "--gl-debug"};
  for (const auto& [flag, value] : flags) args.insert(args.end(), {flag, value});
  const Parsed parsed = parse(args);
  ASSERT_TRUE(parsed.result.config) << parsed.err;
  const DaemonConfig& config = *parsed.result.config;
  EXPECT_EQ(config.host, "0.0.0.0");
  EXPECT_EQ(config.port, 0);
  EXPECT_EQ(config.httpThreads, 4);
  EXPECT_EQ(config.authToken, "s3cret");
  EXPECT_EQ(config.grace, std::chrono::milliseconds(0));
  EXPECT_EQ(config.watchdog, std::chrono::milliseconds(1500));
  EXPECT_EQ(config.logFormat, "text");
  EXPECT_EQ(config.queueDepth, 3);
  EXPECT_EQ(config.deadline, std::chrono::milliseconds(2500));
  EXPECT_EQ(config.sceneCacheBytes, 64ULL << 20);
  EXPECT_EQ(config.testRenderDelay, std::chrono::milliseconds(25));
  EXPECT_EQ(config.limits.maxBodyBytes, 2ULL << 20);
  EXPECT_EQ(config.limits.maxWidth, 800);
  EXPECT_EQ(config.limits.maxHeight, 600);
  EXPECT_EQ(config.limits.maxPixels, 480000);
  EXPECT_EQ(config.limits.maxLights, 10);
  EXPECT_EQ(config.limits.maxVpls, 1000);
  EXPECT_EQ(config.limits.maxTriangles, 12345U);
  EXPECT_EQ(config.limits.maxTextureSize, 1024);
  EXPECT_EQ(config.limits.maxBatch, 5);
  EXPECT_EQ(config.context.logLevel, "debug");

  const lgh::RendererOptions renderer = config.rendererOptions();
  EXPECT_EQ(renderer.backend, lgh::ContextBackend::Surfaceless);
  EXPECT_EQ(renderer.gpuIndex, 1);
  EXPECT_TRUE(renderer.requireGpu);
  EXPECT_TRUE(renderer.glDebug);
  EXPECT_EQ(renderer.assetRoot, std::filesystem::path("/srv/assets"));
  EXPECT_EQ(renderer.maxTriangles, 12345U);
  EXPECT_EQ(renderer.maxTextureSize, 1024);
  EXPECT_EQ(renderer.sceneCacheBytes, 64ULL << 20);
  EXPECT_EQ(renderer.maxTextureBytes, 100ULL << 20);
  EXPECT_EQ(config.metricsPort, 9090);
  EXPECT_EQ(renderer.sceneWorker.memoryBytes, 512ULL << 20);
  EXPECT_EQ(renderer.sceneWorker.timeoutSeconds, 2.5);
  EXPECT_EQ(renderer.sceneWorker.arguments, (std::vector<std::string>{kSceneWorkerFlag, "boom"}));
  const lgh::RequestLimits limits = config.requestLimits();
  EXPECT_EQ(limits.maxWidth, 800);
  EXPECT_EQ(limits.maxHeight, 600);
  EXPECT_EQ(limits.maxPixels, 480000);
  EXPECT_EQ(limits.maxLights, 10);
  EXPECT_EQ(limits.maxVpls, 1000);
  EXPECT_EQ(limits.maxInlineGlbBytes, 2ULL << 20);
}

TEST_F(DaemonConfigTest, SceneWorkerOffParsesInTheDaemon) {
  const Parsed parsed = parse({"--scene-worker", "off"});
  ASSERT_TRUE(parsed.result.config) << parsed.err;
  EXPECT_TRUE(parsed.result.config->rendererOptions().sceneWorker.executable.empty());
  EXPECT_FALSE(parse({"--scene-worker", "maybe"}).result.config);
  EXPECT_FALSE(parse({"--scene-worker-memory-mb", "16"}).result.config) << "below 256";
}

TEST_F(DaemonConfigTest, EnvironmentVariables) {
  setEnv("LGHD_HOST", "::1");
  setEnv("LGHD_PORT", "9001");
  setEnv("LGHD_DEADLINE_SECONDS", "0.25");
  setEnv("LGHD_LOG_FORMAT", "text");
  setEnv("LGHD_MAX_BATCH", "7");
  setEnv("LGHD_BACKEND", "egl-device");
  setEnv("LGHD_LOG_LEVEL", "error");
  setEnv("LGHD_AUTH_TOKEN", "from-env");
  const Parsed parsed = parse({});
  ASSERT_TRUE(parsed.result.config) << parsed.err;
  const DaemonConfig& config = *parsed.result.config;
  EXPECT_EQ(config.host, "::1");
  EXPECT_EQ(config.port, 9001);
  EXPECT_EQ(config.deadline, std::chrono::milliseconds(250));
  EXPECT_EQ(config.logFormat, "text");
  EXPECT_EQ(config.limits.maxBatch, 7);
  EXPECT_EQ(config.context.backend, "egl-device");
  EXPECT_EQ(config.context.logLevel, "error");
  EXPECT_EQ(config.authToken, "from-env");
}

TEST_F(DaemonConfigTest, FlagWinsOverItsVariable) {
  setEnv("LGHD_PORT", "9001");
  setEnv("LGHD_QUEUE_DEPTH", "9");
  const Parsed parsed = parse({"--port", "9002"});
  ASSERT_TRUE(parsed.result.config) << parsed.err;
  EXPECT_EQ(parsed.result.config->port, 9002);
  EXPECT_EQ(parsed.result.config->queueDepth, 9) << "a variable without its flag still counts";
}

TEST_F(DaemonConfigTest, AuthTokenFileIsReadWithoutTrailingWhitespace) {
  const std::string path = writeFile("lghd_token", "  tok en\t \r\n\n");
  const Parsed parsed = parse({"--auth-token-file", path});
  ASSERT_TRUE(parsed.result.config) << parsed.err;
  EXPECT_EQ(parsed.result.config->authToken, "  tok en");
}

TEST_F(DaemonConfigTest, EmptyAuthTokenFileIsRefused) {
  const std::string path = writeFile("lghd_empty_token", " \n");
  const Parsed parsed = parse({"--auth-token-file", path});
  EXPECT_FALSE(parsed.result.config);
  EXPECT_EQ(parsed.result.exitCode, 2);
  EXPECT_EQ(parsed.err, "lghd: the token file " + path + " is empty\n");
}

// A bad command line: no configuration, exit status 2, and a message naming what was wrong.
TEST_F(DaemonConfigTest, BadFlagsExitWithStatus2AndSayWhy) {
  struct Case {
    std::vector<std::string> args;
    std::vector<std::string> mentions;  // what the message must name
  };
  const std::vector<Case> cases{
      {{"--port", "70000"}, {"--port", "70000"}},
      {{"--port", "eighty"}, {"--port", "eighty"}},
      {{"--http-threads", "1"}, {"--http-threads", "1"}},
      {{"--queue-depth", "0"}, {"--queue-depth", "0"}},
      {{"--deadline-seconds", "0"}, {"--deadline-seconds", "0"}},
      {{"--grace-seconds", "-1"}, {"--grace-seconds", "-1"}},
      {{"--watchdog-seconds", "-2"}, {"--watchdog-seconds", "-2"}},
      {{"--log-format", "xml"}, {"--log-format", "xml"}},
      {{"--max-width", "0"}, {"--max-width", "0"}},
      {{"--max-body-mb", "-3"}, {"--max-body-mb", "-3"}},
      {{"--backend", "vulkan"}, {"--backend", "vulkan"}},
      {{"--log-level", "loud"}, {"--log-level", "loud"}},
      {{"--test-render-delay-ms", "700000"}, {"--test-render-delay-ms", "700000"}},
      {{"--auth-token-file", "/nonexistent/lghd-token"}, {"/nonexistent/lghd-token"}},
      {{"--bogus"}, {"--bogus"}},
      {{"--port"}, {"--port"}},
  };
  for (const Case& c : cases) {
    const std::string line = testing::PrintToString(c.args);
    const Parsed parsed = parse(c.args);
    EXPECT_FALSE(parsed.result.config) << line;
    EXPECT_EQ(parsed.result.exitCode, 2) << line;
    EXPECT_EQ(parsed.out, "") << line;
    for (const std::string& mention : c.mentions) {
      EXPECT_NE(parsed.err.find(mention), std::string::npos)
          << line << ": the message does not name " << mention << ":\n"
          << parsed.err;
    }
    EXPECT_NE(parsed.err.find("Run with --help"), std::string::npos) << line << ":\n" << parsed.err;
  }
}

TEST_F(DaemonConfigTest, BadVariableExitsWithStatus2) {
  setEnv("LGHD_QUEUE_DEPTH", "-4");
  const Parsed parsed = parse({});
  EXPECT_FALSE(parsed.result.config);
  EXPECT_EQ(parsed.result.exitCode, 2);
  EXPECT_NE(parsed.err.find("--queue-depth"), std::string::npos) << parsed.err;
}

TEST_F(DaemonConfigTest, HelpListsFlagsWithTheirVariables) {
  const Parsed parsed = parse({"--help"});
  EXPECT_FALSE(parsed.result.config);
  EXPECT_EQ(parsed.result.exitCode, 0);
  EXPECT_NE(parsed.out.find("lghd: headless GPU render service"), std::string::npos);
  for (const char* text : {"--queue-depth", "LGHD_QUEUE_DEPTH", "--max-body-mb", "LGHD_MAX_BODY_MB",
                           "--backend", "LGHD_BACKEND", "docs/DAEMON.md"}) {
    EXPECT_NE(parsed.out.find(text), std::string::npos) << text;
  }
}

TEST_F(DaemonConfigTest, VersionPrintsTheBuild) {
  const Parsed parsed = parse({"--version"});
  EXPECT_FALSE(parsed.result.config);
  EXPECT_EQ(parsed.result.exitCode, 0);
  EXPECT_EQ(parsed.out, std::string("lghd ") + kVersion + "\n");
}

}  // namespace
}  // namespace lghd

namespace lghd {
namespace {

TEST_F(DaemonConfigTest, GpusListsOneWorkerPerDeviceAndDefaultsToGpu) {
  const Parsed defaults = parse({"--gpu", "3"});
  ASSERT_TRUE(defaults.result.config);
  EXPECT_EQ(defaults.result.config->gpuList(), std::vector<int>{3});
  const Parsed listed = parse({"--gpus", "0, 2,2"});
  ASSERT_TRUE(listed.result.config) << listed.err;
  EXPECT_EQ(listed.result.config->gpuList(), (std::vector<int>{0, 2, 2}));
  setEnv("LGHD_GPUS", "1,0");
  const Parsed fromEnv = parse({});
  ASSERT_TRUE(fromEnv.result.config) << fromEnv.err;
  EXPECT_EQ(fromEnv.result.config->gpuList(), (std::vector<int>{1, 0}));
  // All of EGL's devices: this machine has at least its software one.
  const Parsed all = parse({"--gpus", "all"});
  ASSERT_TRUE(all.result.config);
  EXPECT_TRUE(all.result.config->allGpus);
  EXPECT_FALSE(all.result.config->gpuList().empty());
}

TEST_F(DaemonConfigTest, BadGpusAndContextLossHookExitWithStatus2) {
  for (const auto& [args, mention] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"--gpus", "0,x"}, "'x'"},
           {{"--gpus", "0,,1"}, "--gpus"},
           {{"--gpus", " "}, "--gpus"},
           {{"--gpus", "-1"}, "'-1'"},
           {{"--test-context-loss", "1"}, "--test-context-loss"}}) {
    const Parsed parsed = parse(args);
    EXPECT_FALSE(parsed.result.config) << args[1];
    EXPECT_EQ(parsed.result.exitCode, 2) << args[1];
    EXPECT_NE(parsed.err.find(mention), std::string::npos) << args[1] << ": " << parsed.err;
  }
  const Parsed hook = parse({"--test-context-loss", "1:4"});
  ASSERT_TRUE(hook.result.config);
  EXPECT_EQ(hook.result.config->testContextLossGpu, 1);
  EXPECT_EQ(hook.result.config->testContextLossAfter, 4);
}

}  // namespace
}  // namespace lghd

namespace lghd {
namespace {

// Every flag `lghd --help` lists has a row of docs/DAEMON.md's configuration table naming its
// variable ("| `--flag` | `LGHD_VARIABLE` | ..."): the docs cannot fall behind the flags.
TEST_F(DaemonConfigTest, EveryFlagOfHelpHasARowInTheDocsTable) {
  const Parsed parsed = parse({"--help"});
  std::ifstream in(std::string(LGH_SOURCE_DIR) + "/docs/DAEMON.md");
  ASSERT_TRUE(in);
  const std::string docs((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::regex option(R"(^  (--[a-z0-9-]+)[^\n]*\(Env:(LGHD_[A-Z0-9_]+)\))");
  std::istringstream lines(parsed.out);
  int flags = 0;
  for (std::string line; std::getline(lines, line);) {
    std::smatch match;
    if (!std::regex_search(line, match, option)) continue;
    ++flags;
    // A row's first cell may name several flags ("| `--auth-token`, `--auth-token-file` |").
    const std::string flag = "`" + match[1].str() + "`";
    std::string rowText;
    std::istringstream docLines(docs);
    for (std::string docLine; std::getline(docLines, docLine);) {
      if (docLine.rfind("| `--", 0) != 0) continue;
      const std::size_t cellEnd = docLine.find(" | ");
      if (docLine.substr(0, cellEnd).find(flag) != std::string::npos) rowText = docLine;
    }
    ASSERT_FALSE(rowText.empty()) << match[1] << " has no row in docs/DAEMON.md";
    EXPECT_NE(rowText.find("`" + match[2].str() + "`"), std::string::npos)
        << match[1] << "'s row does not name " << match[2] << ": " << rowText;
  }
  EXPECT_GE(flags, 30) << parsed.out;
}

}  // namespace
}  // namespace lghd
