// The scene parser worker's side (see SceneWorkerOptions in lgh/renderer_options.hpp): a program
// started as the worker calls this with the socket it got on file descriptor 3, and returns its
// result from main. It reads load jobs (a SceneSource, an asset root, limits), loads each with the
// glTF loader, and answers the scene or the lgh::Error, until the socket closes.
#pragma once

#include <string>

namespace lgh {

inline constexpr int kSceneWorkerFd = 3;

// `testCrashMarker`, FOR TESTS ONLY: crash (SIGSEGV) on assets whose display name contains it, to
// show that a parser crash fails one request only. Empty: never.
int runSceneParserWorker(int fd, const std::string& testCrashMarker = {});

}  // namespace lgh
