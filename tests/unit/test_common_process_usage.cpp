// The process's resident memory and CPU time as the kernel counts them (process_usage.hpp).
#include <gtest/gtest.h>

#include <sys/mman.h>

#include <cstring>
#include <ctime>

#include "process_usage.hpp"

using namespace nerv;

TEST(commonProcessUsage, MemoryTouchedIsResidentAndStaysInThePeak) {
  const ProcessUsage before = readProcessUsage();
  ASSERT_GT(before.rss_mb, 0.0) << "/proc/self/status unreadable";
  // Mapped and unmapped directly: malloc may keep a freed block (ASan's quarantine does).
  const size_t bytes = 64u << 20;
  void* block = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  ASSERT_NE(block, MAP_FAILED);
  std::memset(block, 1, bytes);  // touched: every page resident
  const ProcessUsage during = readProcessUsage();
  EXPECT_GT(during.rss_mb - before.rss_mb, 56.0) << "64 MiB touched";
  EXPECT_GE(during.rss_peak_mb, during.rss_mb - 0.01);
  munmap(block, bytes);
  const ProcessUsage after = readProcessUsage();
  EXPECT_LT(after.rss_mb, during.rss_mb - 56.0) << "rss_mb is the memory now";
  // The kernel batches a thread's RSS accounting (up to 64 pages): two reads may disagree by that.
  EXPECT_GE(after.rss_peak_mb, during.rss_mb - 1.0) << "the peak remembers";
}

TEST(commonProcessUsage, CpuTimeGrowsWithWork) {
  const ProcessUsage before = readProcessUsage();
  volatile double sink = 0;
  for (int round = 0; round < 1000 && readProcessUsage().cpu_s - before.cpu_s < 0.1; ++round)
    for (int i = 0; i < 1000000; ++i) sink = sink + i * 1e-9;
  EXPECT_GE(readProcessUsage().cpu_s - before.cpu_s, 0.1);
}

TEST(commonProcessUsage, CpuShareIsCpuTimeOverWallTime) {
  CpuShare share;
  share.percentSince(10.0, 1'000'000'000);                           // since start: not checked here
  EXPECT_DOUBLE_EQ(share.percentSince(10.5, 1'001'000'000), 50.0);   // 0.5 s in 1 s
  EXPECT_DOUBLE_EQ(share.percentSince(12.3, 1'002'000'000), 180.0);  // two threads, 1.8 s in 1 s
  EXPECT_DOUBLE_EQ(share.percentSince(12.3, 1'002'000'000), 0.0) << "no time passed";
  EXPECT_DOUBLE_EQ(share.percentSince(12.3, 1'003'000'000), 0.0) << "idle";
}

// The first report's share is over the process's life so far (read from /proc/self/stat): with
// 0.2 s of CPU spent it is far above what a share over the time since 1970 would be (1e-8 %).
TEST(commonProcessUsage, TheFirstShareCountsFromTheProcesssStart) {
  const double start_cpu = readProcessUsage().cpu_s;
  volatile double sink = 0;
  for (int round = 0; round < 2000 && readProcessUsage().cpu_s - start_cpu < 0.2; ++round)
    for (int i = 0; i < 1000000; ++i) sink = sink + i * 1e-9;
  CpuShare share;
  const ProcessUsage u = readProcessUsage();
  timespec now{};
  clock_gettime(CLOCK_REALTIME, &now);
  const double pct = share.percentSince(u.cpu_s, now.tv_sec * 1'000'000LL + now.tv_nsec / 1000);
  EXPECT_GT(pct, 0.01) << "0.2 s of CPU within the test binary's life (minutes at most)";
  EXPECT_LE(pct, 100.0 * 64);
}
