#include "http_helpers.hpp"

#include <zip.h>

#include <sstream>
#include <thread>

#include "daemon_process.hpp"

namespace lghd::test {

httplib::Result postJson(httplib::Client& client, const std::string& path, const json& body,
                         const httplib::Headers& headers) {
  return client.Post(path.c_str(), headers, body.dump(), "application/json");
}

json errorOf(const httplib::Result& result) {
  if (!result) {
    ADD_FAILURE() << "no answer: " << httplib::to_string(result.error());
    return {};
  }
  EXPECT_EQ(result->get_header_value("Content-Type"), "application/json");
  const json body = json::parse(result->body, nullptr, false);
  if (!body.is_object() || !body.contains("error")) {
    ADD_FAILURE() << "not a JSON error body: " << result->body;
    return {};
  }
  const json& error = body["error"];
  EXPECT_TRUE(error.contains("code") && error.contains("message") && error.contains("field"))
      << body.dump();
  return error;
}

json expectError(const httplib::Result& result, int status, const std::string& code) {
  if (!result) {
    ADD_FAILURE() << "no answer: " << httplib::to_string(result.error());
    return {};
  }
  EXPECT_EQ(result->status, status) << result->body;
  json error = errorOf(result);
  EXPECT_EQ(error.value("code", ""), code) << error.dump();
  return error;
}

lgh::image_io::Decoded decodeBody(const std::string& bytes, const std::string& what) {
  return lgh::image_io::decode(std::vector<std::uint8_t>(bytes.begin(), bytes.end()), what);
}

double metricValue(const std::string& exposition, const std::string& series) {
  std::istringstream lines(exposition);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.size() > series.size() && line.compare(0, series.size(), series) == 0 &&
        line[series.size()] == ' ') {
      return std::stod(line.substr(series.size() + 1));
    }
  }
  return 0.0;
}

double waitForMetric(httplib::Client& client, const std::string& series, double atLeast) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  double value = 0.0;
  while (std::chrono::steady_clock::now() < end) {
    const auto metrics = client.Get("/metrics");
    value = metrics ? metricValue(metrics->body, series) : 0.0;
    if (value >= atLeast) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return value;
}

namespace {

// Calls `each(archive, index, stat)` for every member of the ZIP archive in `bytes`.
template <class Each>
void forEachZipMember(const std::string& bytes, Each each) {
  zip_error_t error;
  zip_error_init(&error);
  zip_source_t* source = zip_source_buffer_create(bytes.data(), bytes.size(), 0, &error);
  zip_t* archive = source ? zip_open_from_source(source, ZIP_RDONLY, &error) : nullptr;
  if (archive == nullptr) {
    ADD_FAILURE() << "not a ZIP archive: " << zip_error_strerror(&error);
    if (source) zip_source_free(source);
    zip_error_fini(&error);
    return;
  }
  const zip_int64_t count = zip_get_num_entries(archive, 0);
  for (zip_int64_t i = 0; i < count; ++i) {
    zip_stat_t stat;
    zip_stat_index(archive, static_cast<zip_uint64_t>(i), 0, &stat);
    each(archive, static_cast<zip_uint64_t>(i), stat);
  }
  zip_close(archive);
  zip_error_fini(&error);
}

}  // namespace

std::map<std::string, std::string> unzip(const std::string& bytes) {
  std::map<std::string, std::string> members;
  forEachZipMember(bytes, [&](zip_t* archive, zip_uint64_t index, const zip_stat_t& stat) {
    std::string content(static_cast<std::size_t>(stat.size), '\0');
    zip_file_t* file = zip_fopen_index(archive, index, 0);
    zip_fread(file, content.data(), content.size());
    zip_fclose(file);
    members[stat.name] = std::move(content);
  });
  return members;
}

std::map<std::string, std::string> zipComments(const std::string& bytes) {
  std::map<std::string, std::string> comments;
  forEachZipMember(bytes, [&](zip_t* archive, zip_uint64_t index, const zip_stat_t& stat) {
    zip_uint32_t length = 0;
    const char* comment = zip_file_get_comment(archive, index, &length, 0);
    comments[stat.name] = comment != nullptr ? std::string(comment, length) : std::string();
  });
  return comments;
}

httplib::MultipartFormData filePart(const std::string& relativePath,
                                    const std::string& uploadName) {
  const std::string name =
      uploadName.empty() ? std::filesystem::path(relativePath).filename().string() : uploadName;
  return {"file", readFile(assimpDir() / relativePath), name, "application/octet-stream"};
}

httplib::MultipartFormData requestPart(const json& request) {
  return {"request", request.dump(), "", "application/json"};
}

}  // namespace lghd::test
