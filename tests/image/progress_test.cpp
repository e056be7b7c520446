// ProgressBar: the line it formats, its rate limit, and its silence when not on a terminal.
#include <cstdio>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "host/util/progress.h"

namespace gc {
namespace {

std::string read_back(std::FILE* f)
{
    std::fflush(f);
    std::rewind(f);
    std::string s;
    for (int c; (c = std::fgetc(f)) != EOF;) s.push_back(char(c));
    return s;
}

TEST(Progress, FormatLine)
{
    const std::string line = ProgressBar::format_line("render", 25, 100, 10.0, "spp", 20);
    std::printf("%s\n", line.c_str());
    EXPECT_EQ(line, "render  [#####...............]  25%  00:10 elapsed  ETA 00:30  2.50 spp/s");
    EXPECT_NE(ProgressBar::format_line("r", 0, 100, 1.0, "spp").find("ETA --:--"), std::string::npos);
    EXPECT_NE(ProgressBar::format_line("r", 100, 100, 1.0, "spp").find("100%"), std::string::npos);
}

TEST(Progress, FormatRateAndDuration)
{
    EXPECT_EQ(ProgressBar::format_rate(3.21e6, "rays"), "3.21 Mrays/s");
    EXPECT_EQ(ProgressBar::format_rate(45600, "spp"), "45.6 kspp/s");
    EXPECT_EQ(ProgressBar::format_rate(999, "spp"), "999 spp/s");
    EXPECT_EQ(ProgressBar::format_duration(59.4), "00:59");
    EXPECT_EQ(ProgressBar::format_duration(3725), "1:02:05");
    EXPECT_EQ(ProgressBar::format_duration(-1), "--:--");
}

TEST(Progress, SilentWhenNotATerminalOrQuiet)
{
    std::FILE* f = std::tmpfile();
    ASSERT_NE(f, nullptr);
    {
        ProgressBar bar("render", 10, {.out = f});  // a regular file is not a TTY
        EXPECT_FALSE(bar.enabled());
        bar.update(5);
        bar.finish();
        ProgressBar quiet("render", 10, {.quiet = true, .out = f, .force = true});
        EXPECT_FALSE(quiet.enabled());
        quiet.update(5);
        quiet.finish();
    }
    EXPECT_EQ(read_back(f), "");
    std::fclose(f);
}

TEST(Progress, RateLimitedThenFinalLine)
{
    std::FILE* f = std::tmpfile();
    ASSERT_NE(f, nullptr);
    {
        ProgressBar bar("render", 1000, {.out = f, .force = true, .unit = "spp", .min_interval_ms = 500});
        ASSERT_TRUE(bar.enabled());
        for (uint64_t i = 1; i <= 1000; ++i) bar.update(i);  // a tight loop: far under 500 ms
        std::this_thread::sleep_for(std::chrono::milliseconds(550));
        bar.update(1000);
        bar.finish();
        bar.finish();  // idempotent
    }
    const std::string out = read_back(f);
    size_t draws = 0;
    for (char c : out) draws += c == '\r';
    std::printf("draws: %zu for 1001 updates + finish\n", draws);
    EXPECT_EQ(draws, 3u);  // first update, the one after the sleep, finish
    EXPECT_EQ(out.back(), '\n');
    EXPECT_NE(out.rfind("100%"), std::string::npos);
    std::fclose(f);
}

TEST(Progress, DestructorEndsAnUnfinishedLine)
{
    std::FILE* f = std::tmpfile();
    ASSERT_NE(f, nullptr);
    {
        ProgressBar bar("render", 10, {.out = f, .force = true});
        bar.update(3);
    }
    const std::string out = read_back(f);
    EXPECT_NE(out.find(" 30%"), std::string::npos) << out;
    EXPECT_EQ(out.back(), '\n');
    EXPECT_EQ(out.find("100%"), std::string::npos) << "an abandoned bar must not claim completion";
    std::fclose(f);
}

}  // namespace
}  // namespace gc
