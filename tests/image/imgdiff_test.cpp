// geocold-imgdiff end to end: metrics printed, exit codes 0 / 2 / 3 / 6, heat map written.
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>

#include <gtest/gtest.h>

#include "host/image/image_io.h"
#include "temp_dir.h"

namespace gc {
namespace {

class ImgDiff : public test::TempDirTest {
protected:
    int run(const std::string& args)
    {
        const std::string cmd = std::string(GC_IMGDIFF_EXE) + " " + args + " > " + path("stdout.txt").string() + " 2>&1";
        const int status = std::system(cmd.c_str());
        m_output = slurp(path("stdout.txt"));
        std::printf("$ geocold-imgdiff %s\n%s", args.c_str(), m_output.c_str());
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    }
    std::string write(const std::string& name, float v)
    {
        Film f(8, 8);
        f.fill({v, v, v, 1});
        write_image(path(name), f, {});
        return path(name).string();
    }
    std::string m_output;
};

TEST_F(ImgDiff, EqualImagesExitZero)
{
    const std::string a = write("a.pfm", 0.5f);
    EXPECT_EQ(run(a + " " + a + " --rel-mse-max 0"), 0);
    EXPECT_NE(m_output.find("rel_mse            0"), std::string::npos);
}

TEST_F(ImgDiff, ThresholdExceededExitsSix)
{
    const std::string a = write("a.pfm", 0.6f), b = write("b.pfm", 0.5f);
    // rel_mse = 0.01 / 0.26 = 0.0385.
    EXPECT_EQ(run(a + " " + b + " --rel-mse-max 0.01"), 6);
    EXPECT_NE(m_output.find("rel_mse            0.03846"), std::string::npos);
    EXPECT_EQ(run(a + " " + b + " --rel-mse-max 0.05"), 0);
}

TEST_F(ImgDiff, UnreadableInputExitsThree)
{
    const std::string a = write("a.pfm", 0.5f);
    EXPECT_EQ(run(a + " " + path("missing.pfm").string()), 3);
    EXPECT_NE(m_output.find("missing.pfm"), std::string::npos);
}

TEST_F(ImgDiff, BadUsageExitsTwo)
{
    EXPECT_EQ(run("only-one.pfm"), 2);
    EXPECT_EQ(run("a.pfm b.pfm --rel-mse-max banana"), 2);
}

TEST_F(ImgDiff, HeatmapAndZTest)
{
    const std::string a = write("a.pfm", 0.5f);
    const std::string var = write("var.pfm", 0.01f);
    EXPECT_EQ(run(a + " " + a + " --variance " + var + " --spp 16 --heatmap " + path("h.ppm").string()), 0);
    EXPECT_TRUE(std::filesystem::exists(path("h.ppm")));
    EXPECT_NE(m_output.find("64/64 pixels pass"), std::string::npos);
    const std::string shifted = write("s.pfm", 0.6f);
    EXPECT_EQ(run(shifted + " " + a + " --variance " + var + " --spp 64"), 6);  // z = 8
}

}  // namespace
}  // namespace gc
