// The thread count of a request: 0 takes the cores that other processes leave free.
#include "core/common/threads.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <fstream>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace pcl_ncut_seg {
namespace {

int processors() {
  return static_cast<int>(std::max(1L, sysconf(_SC_NPROCESSORS_ONLN)));
}

// The library is built with OpenMP (CMakeLists.txt requires it); the tests are not.
TEST(Threads, AnExplicitRequestIsKeptUpToTheProcessors) {
  EXPECT_EQ(usableThreads(1), 1);
  const int most = usableThreads(1000);
  EXPECT_GE(most, processors());
  EXPECT_LT(most, 1000);
}

TEST(Threads, ZeroGivesBetweenOneAndAllThreads) {
  const int threads = usableThreads(0);
  EXPECT_GE(threads, 1);
  EXPECT_LE(threads, usableThreads(1000));
}

/// As many processes as processors spin: no core is free, so 0 asks for one thread.
TEST(Threads, ABusyMachineGetsOneThread) {
  if (!std::ifstream("/proc/loadavg"))
    GTEST_SKIP() << "no /proc/loadavg: the count of free cores is not known here";
  const int cores = processors();
  std::vector<pid_t> spinners;
  for (int i = 0; i < cores; ++i) {
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) { // spin until killed, or for 30 s at most
      const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(30);
      while (std::chrono::steady_clock::now() < end) {
      }
      _exit(0);
    }
    spinners.push_back(pid);
  }
  // The spinners are running (or waiting to run) once they are scheduled.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (otherRunningThreads() < cores && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  const int others = otherRunningThreads();
  // usableThreads keeps a reading for 10 ms: one taken before the spinners ran is stale by now.
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  const int threads = usableThreads(0);
  for (const pid_t pid : spinners) {
    kill(pid, SIGKILL);
    waitpid(pid, nullptr, 0);
  }
  EXPECT_GE(others, cores);
  EXPECT_EQ(threads, 1);
}

} // namespace
} // namespace pcl_ncut_seg
