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

// A resumed run's estimate comes from its own pace since it started (issue 24: a load resumed at
// 91.6% said "ETA 1 s" after 11 s, as if it had done all 91.6% in them).
TEST(Progress, EstimatesFromWhereThisRunStarted) {
  double now = 100.0;
  aniso::Progress progress(
      aniso::make_silent_logger(), "load", 0.6, 10.0, [&now] { return now; }, 0.3);
  now = 120.0; // 0.15 of strain in 20 s; 0.15 left
  EXPECT_EQ(progress.line(0.45), "load: 75.0% (0.45 of 0.6), elapsed 20 s, ETA 20 s");
  EXPECT_EQ(progress.line(0.3), "load: 50.0% (0.3 of 0.6), elapsed 20 s, ETA ?"); // no pace yet
}

TEST(Progress, DurationFormat) {
  EXPECT_EQ(aniso::format_duration(12.4), "12 s");
  EXPECT_EQ(aniso::format_duration(185), "3 min 05 s");
  EXPECT_EQ(aniso::format_duration(3720), "1 h 02 min");
  EXPECT_EQ(aniso::format_duration(-1), "?");
}

} // namespace
