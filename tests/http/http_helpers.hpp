// Assertions and decoding shared by the HTTP tests.
#pragma once

#include <map>
#include <string>

#include <gtest/gtest.h>
#include <httplib.h>
#include <nlohmann/json.hpp>

#include "lgh/image.hpp"

namespace lghd::test {

using json = nlohmann::json;

httplib::Result postJson(httplib::Client& client, const std::string& path, const json& body,
                         const httplib::Headers& headers = {});

// The JSON error body's "error" object; a test failure when the answer is not one.
json errorOf(const httplib::Result& result);

// Checks status, JSON error body and its code; returns the error object.
json expectError(const httplib::Result& result, int status, const std::string& code);

lgh::image_io::Decoded decodeBody(const std::string& bytes, const std::string& what = "response");

// The value of one series in a Prometheus exposition ("name{labels}" exactly as printed); 0 when
// it is absent.
double metricValue(const std::string& exposition, const std::string& series);

// Polls /metrics until `series` reaches at least `atLeast` (the daemon counts a request just
// after its answer left) or 5 s pass; returns the last value seen.
double waitForMetric(httplib::Client& client, const std::string& series, double atLeast);

// Member name -> bytes of a ZIP archive in memory.
std::map<std::string, std::string> unzip(const std::string& bytes);
// Member name -> file comment (empty for none) of a ZIP archive in memory.
std::map<std::string, std::string> zipComments(const std::string& bytes);

// A multipart "file" part holding a file of the assimp test models (path relative to it),
// uploaded under `uploadName` (default: the file's own name).
httplib::MultipartFormData filePart(const std::string& relativePath,
                                    const std::string& uploadName = "");
httplib::MultipartFormData requestPart(const json& request);

}  // namespace lghd::test
