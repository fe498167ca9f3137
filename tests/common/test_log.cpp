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

// A resumed run's estimate comes from its own pace since it started (a load resumed at
// 91.6% said "ETA 1 s" after 11 s, as if it had done all 91.6% in them).
TEST(Progress, EstimatesFromWhereThisRunStarted) {
  double now = 100.0;
  aniso::Progress progress(
      aniso::make_silent_logger(), "load", 0.6, 10.0, [&now] { return now; }, 0.3);
  now = 120.0; // 0.15 of strain in 20 s; 0.15 left
  EXPECT_EQ(progress.line(0.45), "load: 75.0% (0.45 of 0.6), elapsed 20 s, ETA 20 s");
  EXPECT_EQ(progress.line(0.3), "load: 50.0% (0.3 of 0.6), elapsed 20 s, ETA ?"); // no pace yet
}

// A stage that slows down near its end: the estimate follows the recent pace (a paper-size
// compaction said "ETA 8 s" for 20 minutes at 98% while it crept towards seizing).
TEST(Progress, EstimatesFromTheRecentPace) {
  double now = 0.0;
  aniso::Progress progress(aniso::make_silent_logger(), "compaction", 1.0, 10.0, [&now] { return now; });
  double done = 0.0;
  for (int k = 1; k <= 6; ++k) { // 0.9 in the first minute
    now = 10.0 * k;
    done = 0.15 * k;
    EXPECT_TRUE(progress.update(done));
  }
  for (int k = 7; k <= 60; ++k) { // then 0.001 per 10 s
    now = 10.0 * k;
    done += 0.001;
    EXPECT_TRUE(progress.update(done));
  }
  // 10 min elapsed: the last 5 min advanced 0.030, so the 0.046 left take about 7.7 min (the pace
  // of the whole run would say 40 s).
  EXPECT_EQ(progress.line(done), "compaction: 95.4% (0.954 of 1), elapsed 10 min 00 s, ETA 7 min 40 s");
}

TEST(Progress, PrintsTheDetailOnlyWhenItPrints) {
  double now = 0.0;
  int asked = 0;
  aniso::Progress progress(aniso::make_silent_logger(), "x", 1.0, 10.0, [&now] { return now; });
  const auto detail = [&asked] {
    ++asked;
    return std::string("cell held");
  };
  now = 5.0;
  EXPECT_FALSE(progress.update(0.1, detail));
  now = 10.0;
  EXPECT_TRUE(progress.update(0.2, detail));
  EXPECT_EQ(asked, 1);
}

TEST(Progress, DurationFormat) {
  EXPECT_EQ(aniso::format_duration(12.4), "12 s");
  EXPECT_EQ(aniso::format_duration(185), "3 min 05 s");
  EXPECT_EQ(aniso::format_duration(3720), "1 h 02 min");
  EXPECT_EQ(aniso::format_duration(-1), "?");
}

} // namespace
