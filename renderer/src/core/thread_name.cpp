#include "lgh/thread_name.hpp"

#include <pthread.h>

#include <algorithm>
#include <string>

namespace lgh {

void nameThisThread(std::string_view name) {
  constexpr std::size_t kLinuxNameBytes = 15;
  const std::string kept(name.substr(0, std::min(name.size(), kLinuxNameBytes)));
  // Naming is for people reading a process list: a refusal changes nothing else.
  (void)pthread_setname_np(pthread_self(), kept.c_str());
}

}  // namespace lgh
