// Frame timing summaries (terrasynth_host/frame_stats.h), no window.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include "terrasynth_host/frame_stats.h"

namespace terrasynth::host {
namespace {

TEST(FrameStats, SummaryIsTheSortedNearestRank) {
    std::vector<double> v(100);
    std::iota(v.begin(), v.end(), 1.0);  // 1..100
    std::reverse(v.begin(), v.end());
    const SeriesSummary s = summarize(v);
    EXPECT_EQ(s.count, 100u);
    EXPECT_DOUBLE_EQ(s.median, 50.5);
    EXPECT_DOUBLE_EQ(s.p95, 95.0);
    EXPECT_DOUBLE_EQ(s.max, 100.0);
    EXPECT_DOUBLE_EQ(s.mean, 50.5);
    const SeriesSummary one = summarize({7.0});
    EXPECT_DOUBLE_EQ(one.median, 7.0);
    EXPECT_DOUBLE_EQ(one.p95, 7.0);
    EXPECT_EQ(summarize({}).count, 0u);
}

TEST(FrameStats, MainThreadIsTheFrameLessTheGlDrawAndScreenshots) {
    FrameTiming t;
    t.events_ms = 1;
    t.app_ms = 2;
    t.update_ms = 3;
    t.cull_ms = 4;
    t.draw_ms = 50;
    t.overlay_ms = 5;
    t.swap_ms = 6;
    t.screenshot_ms = 20;
    t.frame_ms = 92;
    EXPECT_DOUBLE_EQ(t.glMs(), 61.0);
    EXPECT_DOUBLE_EQ(t.mainThreadMs(), 11.0);
    FrameTimeSeries series;
    series.add(t);
    t.cull_ms = 8;
    series.add(t);
    EXPECT_EQ(series.column(&FrameTiming::cull_ms), (std::vector<double>{4.0, 8.0}));
    EXPECT_EQ(series.gl(), (std::vector<double>{61.0, 61.0}));
    EXPECT_EQ(series.mainThread().size(), 2u);
}

}  // namespace
}  // namespace terrasynth::host
