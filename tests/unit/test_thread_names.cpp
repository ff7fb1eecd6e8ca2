// Thread names (lgh/thread_name.hpp): what `top -H` and /proc show for lghd's own threads.
#include <gtest/gtest.h>

#include <sys/syscall.h>
#include <unistd.h>

#include <atomic>
#include <fstream>
#include <mutex>
#include <set>
#include <string>
#include <thread>

#include "lgh/task_pool.hpp"
#include "lgh/thread_name.hpp"

namespace lgh {
namespace {

std::string nameOfThisThread() {
  const auto tid = static_cast<long>(::syscall(SYS_gettid));
  std::ifstream comm("/proc/self/task/" + std::to_string(tid) + "/comm");
  std::string name;
  std::getline(comm, name);
  return name;
}

// The name /proc shows for a new thread that named itself `name`.
std::string nameSeenAfterNaming(const std::string& name) {
  std::string seen;
  std::thread([&] {
    nameThisThread(name);
    seen = nameOfThisThread();
  }).join();
  return seen;
}

TEST(ThreadNames, AThreadIsNamedAsAsked) { EXPECT_EQ(nameSeenAfterNaming("lgh-test"), "lgh-test"); }

TEST(ThreadNames, ANameIsCutAtLinuxsFifteenBytes) {
  EXPECT_EQ(nameSeenAfterNaming("lgh-a-name-longer-than-fifteen-bytes"), "lgh-a-name-long");
}

TEST(ThreadNames, TaskPoolWorkersCarryThePoolsNameAndTheirIndex) {
  std::mutex mutex;
  std::set<std::string> names;
  {
    TaskPool pool(3, "lgh-encode");
    // Each task holds its worker until all three have started, so every worker runs one.
    std::atomic<int> started{0};
    for (int i = 0; i < 3; ++i) {
      pool.submit([&] {
        ++started;
        while (started.load() < 3) std::this_thread::yield();
        const std::lock_guard lock(mutex);
        names.insert(nameOfThisThread());
      });
    }
    pool.waitIdle();
  }
  EXPECT_EQ(names, (std::set<std::string>{"lgh-encode-0", "lgh-encode-1", "lgh-encode-2"}));
}

}  // namespace
}  // namespace lgh
