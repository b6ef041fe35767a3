// GL tests of the engine's GL layer under headless EGL (llvmpipe in CI): GpuTimer and PassTimer in both
// clocks (timer queries, wall clock around glFinish). The binary's files share one context and the GlTest
// fixture (GlLayerTest.h).
#include "GlLayerTest.h"

namespace {

using namespace pacifica::gltest;

// GpuTimer
// ---------------------------------------------------------------------------------------------------------

using GpuTimerTest = GlTest;

TEST_F(GpuTimerTest, WallClockTimesOneSpan) {
    SmallDraw scene;
    gl::GpuTimer timer(gl::GpuTimer::Clock::WallAroundFinish);
    EXPECT_EQ(timer.clock(), gl::GpuTimer::Clock::WallAroundFinish);
    EXPECT_TRUE(contains(timer.clockName(), "glFinish")) << timer.clockName();
    timer.begin();
    scene.draw();
    timer.end();
    ASSERT_EQ(timer.samples().size(), 1u);
    const double ms = timer.samples()[0];
    EXPECT_TRUE(std::isfinite(ms)) << ms;
    EXPECT_GT(ms, 0.0);
    EXPECT_LT(ms, 60'000.0) << "a 16x16 triangle cannot take a minute";
    const std::optional<double> latest = timer.poll();
    ASSERT_TRUE(latest.has_value());
    EXPECT_EQ(*latest, ms);
    EXPECT_FALSE(timer.poll().has_value()) << "poll() hands out each measurement once";

    // The draw really happened: the whole scene is the solid colour.
    std::vector<float> rgba;
    scene.targets.readScene(rgba);
    ASSERT_EQ(rgba.size(), 16u * 16u * 4u);
    EXPECT_EQ(rgba[0], 0.5f);
    EXPECT_EQ(rgba[rgba.size() - 2], 1.0f);
}

TEST_F(GpuTimerTest, MisuseThrowsLogicError) {
    gl::GpuTimer timer(gl::GpuTimer::Clock::WallAroundFinish);
    const std::string endFirst = messageOf<std::logic_error>([&] { timer.end(); });
    EXPECT_TRUE(endFirst.starts_with("GpuTimer::end()")) << endFirst;
    timer.begin();
    const std::string twice = messageOf<std::logic_error>([&] { timer.begin(); });
    EXPECT_TRUE(twice.starts_with("GpuTimer::begin()")) << twice;
    timer.end(); // the span opened by the first begin() is still the open one
    EXPECT_EQ(timer.samples().size(), 1u);
    EXPECT_THROW(timer.end(), std::logic_error);

    gl::GpuTimer queries(gl::GpuTimer::Clock::TimerQuery);
    EXPECT_THROW(queries.end(), std::logic_error);
    queries.begin();
    EXPECT_THROW(queries.begin(), std::logic_error);
    queries.end();
    glFinish();

    EXPECT_THROW(gl::GpuTimer(gl::GpuTimer::Clock::WallAroundFinish, 0), std::logic_error);
}

TEST_F(GpuTimerTest, ContextChoosesWallClockOnSoftwareRenderers) {
    gl::GpuTimer timer(info());
    // docs/PLATFORM.md: GL_TIME_ELAPSED is wrong on llvmpipe, right on hardware drivers.
    if (info().software)
        EXPECT_EQ(timer.clock(), gl::GpuTimer::Clock::WallAroundFinish) << info().renderer;
    else
        EXPECT_EQ(timer.clock(), gl::GpuTimer::Clock::TimerQuery) << info().renderer;
}

TEST_F(GpuTimerTest, TimerQueryRingSurvivesMoreSpansThanSlots) {
    SmallDraw scene;
    gl::GpuTimer timer(gl::GpuTimer::Clock::TimerQuery, 4);
    EXPECT_EQ(timer.clock(), gl::GpuTimer::Clock::TimerQuery);
    EXPECT_TRUE(contains(timer.clockName(), "GL_TIME_ELAPSED")) << timer.clockName();
    for (int i = 0; i < 6; ++i) {
        EXPECT_NO_THROW(timer.begin());
        scene.draw();
        EXPECT_NO_THROW(timer.end());
    }
    glFinish();
    (void)timer.poll();
    // Spans 5 and 6 had to wait for spans 1 and 2; after glFinish the other four are available (llvmpipe's
    // values are wrong, docs/PLATFORM.md, so only their sanity is checked).
    ASSERT_GE(timer.samples().size(), 1u);
    EXPECT_EQ(timer.samples().size(), 6u);
    for (double ms : timer.samples()) {
        EXPECT_TRUE(std::isfinite(ms)) << ms;
        EXPECT_GE(ms, 0.0);
    }
}

// ---------------------------------------------------------------------------------------------------------

// PassTimer
// ---------------------------------------------------------------------------------------------------------

using PassTimerTest = GlTest;

TEST_F(PassTimerTest, WallClockAttributesEachSpanToTheMarkedPass) {
    SmallDraw scene;
    gl::PassTimer timer(gl::GpuTimer::Clock::WallAroundFinish, 3);
    EXPECT_TRUE(contains(timer.clockName(), "glFinish")) << timer.clockName();
    EXPECT_FALSE(timer.poll().has_value()) << "no frame yet";
    timer.beginFrame();
    scene.draw();
    timer.mark(0);
    std::this_thread::sleep_for(std::chrono::milliseconds(30)); // pass 2's span: 30 ms of nothing
    timer.mark(2);
    scene.draw();
    timer.mark(0); // a pass marked twice sums its spans
    timer.endFrame();
    const auto ms = timer.poll();
    ASSERT_TRUE(ms.has_value());
    ASSERT_EQ(ms->size(), 3u);
    EXPECT_GT((*ms)[0], 0.0);
    EXPECT_EQ((*ms)[1], 0.0) << "pass 1 was never marked";
    EXPECT_GE((*ms)[2], 29.0);
    EXPECT_LT((*ms)[2], 5000.0);
    EXPECT_FALSE(timer.poll().has_value()) << "poll() hands out each frame once";
}

TEST_F(PassTimerTest, MisuseThrowsLogicError) {
    for (gl::GpuTimer::Clock clock :
         {gl::GpuTimer::Clock::WallAroundFinish, gl::GpuTimer::Clock::TimerQuery}) {
        gl::PassTimer timer(clock, 2);
        const std::string markFirst = messageOf<std::logic_error>([&] { timer.mark(0); });
        EXPECT_TRUE(markFirst.starts_with("PassTimer::mark()")) << markFirst;
        EXPECT_THROW(timer.endFrame(), std::logic_error);
        timer.beginFrame();
        EXPECT_THROW(timer.beginFrame(), std::logic_error);
        const std::string outside = messageOf<std::logic_error>([&] { timer.mark(2); });
        EXPECT_TRUE(contains(outside, "pass 2 outside [0, 2)")) << outside;
        timer.mark(1);
        timer.endFrame();
        glFinish();
        timer.drain();
    }
    EXPECT_THROW(gl::PassTimer(gl::GpuTimer::Clock::WallAroundFinish, 0), std::logic_error);
    EXPECT_THROW(gl::PassTimer(gl::GpuTimer::Clock::TimerQuery, 1, 0), std::logic_error);
}

TEST_F(PassTimerTest, TimestampRingSurvivesMoreFramesThanSlots) {
    SmallDraw scene;
    gl::PassTimer timer(gl::GpuTimer::Clock::TimerQuery, 2, 3);
    EXPECT_TRUE(contains(timer.clockName(), "GL_TIMESTAMP")) << timer.clockName();
    // A GpuTimer span around the frames: glQueryCounter is allowed inside GL_TIME_ELAPSED (they nest).
    gl::GpuTimer outer(gl::GpuTimer::Clock::TimerQuery);
    outer.begin();
    int frames = 0;
    for (int i = 0; i < 7; ++i) {
        timer.beginFrame(); // frames 4..7 have to wait for frames 1..4's timestamps
        scene.draw();
        timer.mark(0);
        scene.draw();
        timer.mark(1);
        timer.endFrame();
        frames += timer.poll().has_value() ? 1 : 0;
    }
    outer.end();
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    glFinish();
    timer.drain();
    const auto last = timer.poll();
    ASSERT_TRUE(last.has_value()) << "drain() leaves the newest frame for poll()";
    ASSERT_EQ(last->size(), 2u);
    for (double ms : *last) { // llvmpipe's timestamps are not meaningful (docs/PLATFORM.md): sanity only
        EXPECT_TRUE(std::isfinite(ms)) << ms;
        EXPECT_GE(ms, 0.0);
    }
    EXPECT_LE(frames, 7);
}

// ---------------------------------------------------------------------------------------------------------

} // namespace
