#include "gl/uniform_locations.hpp"

#include <map>
#include <string>
#include <unordered_map>
#include <utility>

namespace lgh::gl {
namespace {

using Locations = std::unordered_map<std::string, GLint>;

// A context is current on one thread at a time, and its programs are used and deleted there.
std::map<std::pair<const Api*, GLuint>, Locations>& locationTable() {
  thread_local std::map<std::pair<const Api*, GLuint>, Locations> table;
  return table;
}

}  // namespace

GLint uniformLocation(GLuint program, const char* name) {
  Locations& locations = locationTable()[{currentApi(), program}];
  const auto [entry, added] = locations.try_emplace(name, -1);
  if (added) entry->second = glGetUniformLocation(program, name);
  return entry->second;
}

void forgetUniformLocations(const Api* context) {
  auto& table = locationTable();
  auto first = table.lower_bound({context, 0});
  auto last = first;
  while (last != table.end() && last->first.first == context) ++last;
  table.erase(first, last);
}

}  // namespace lgh::gl
