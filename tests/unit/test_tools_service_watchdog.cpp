// The supervisor's watchdog (service_watchdog.hpp): a process is hung once it has
// sent no health for its allowance, the start-up allowance before its first
// report, never when the watchdog is off, and reports of an earlier process do
// not count for a restarted one.
#include <gtest/gtest.h>

#include "service_watchdog.hpp"

using namespace nerv;

TEST(toolsServiceWatchdog, SilentLongerThanTheAllowanceAfterAReportIsHung) {
  ServiceWatchdog w({5.0, 30.0});
  w.started(100.0);
  w.reported(101.0);
  EXPECT_FALSE(w.hung(105.9));
  EXPECT_TRUE(w.hung(106.1));
  EXPECT_NEAR(w.silentFor(106.1), 5.1, 1e-9);
  w.reported(106.2);  // a late report clears it again
  EXPECT_FALSE(w.hung(106.3));
  EXPECT_TRUE(w.hasReported());
}

TEST(toolsServiceWatchdog, RegularReportsNeverHang) {
  ServiceWatchdog w({2.0, 30.0});
  w.started(0.0);
  for (int i = 1; i <= 600; ++i) {
    w.reported(i * 1.0);
    ASSERT_FALSE(w.hung(i * 1.0 + 1.9)) << "at " << i;
  }
}

TEST(toolsServiceWatchdog, BeforeTheFirstReportTheStartUpAllowanceHolds) {
  ServiceWatchdog w({5.0, 30.0});
  w.started(10.0);
  EXPECT_FALSE(w.hung(25.0)) << "a long warm-up is not a hang";
  EXPECT_FALSE(w.hung(39.9));
  EXPECT_TRUE(w.hung(40.1)) << "no report at all within the start-up allowance";
  EXPECT_FALSE(w.hasReported());
}

TEST(toolsServiceWatchdog, ReportsFromBeforeARestartDoNotCount) {
  ServiceWatchdog w({5.0, 30.0});
  w.started(0.0);
  w.reported(3.0);
  w.started(50.0);  // restarted: the same pid may report again, or old reports linger
  w.reported(3.0);
  EXPECT_FALSE(w.hasReported());
  EXPECT_FALSE(w.hung(60.0)) << "the new process is still in its start-up allowance";
  EXPECT_TRUE(w.hung(80.5));
}

TEST(toolsServiceWatchdog, OffNeverHangs) {
  ServiceWatchdog w({0.0, 30.0});
  w.started(0.0);
  EXPECT_FALSE(w.hung(1e6));
  w.reported(1.0);
  EXPECT_FALSE(w.hung(1e6));
}
