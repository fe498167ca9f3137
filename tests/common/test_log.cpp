// Progress: prints only when the wall-clock interval has passed, with a correct ETA.
#include "common/log.hpp"

#include <gtest/gtest.h>

namespace {

TEST(Progress, ThrottlesAndEstimatesRemainingTime) {
  double now = 100.0;
  aniso::Progress progress(aniso::make_silent_logger(), "load", 0.6, 10.0, [&now] { return now; });
  now = 105.0;
  EXPECT_FALSE(progress.update(0.1)); // 5 s < 10 s interval
  now = 120.0;
  EXPECT_TRUE(progress.update(0.15)); // 20 s elapsed, a quarter done
  EXPECT_EQ(progress.line(0.15), "load: 25.0% (0.15 of 0.6), elapsed 20 s, ETA 1 min 00 s");
  now = 125.0;
  EXPECT_FALSE(progress.update(0.2));
}

TEST(Progress, DurationFormat) {
  EXPECT_EQ(aniso::format_duration(12.4), "12 s");
  EXPECT_EQ(aniso::format_duration(185), "3 min 05 s");
  EXPECT_EQ(aniso::format_duration(3720), "1 h 02 min");
  EXPECT_EQ(aniso::format_duration(-1), "?");
}

} // namespace
