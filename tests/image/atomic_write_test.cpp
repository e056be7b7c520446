// A failed write must leave the previous file untouched and no temp file behind. The tests
// run as root, so permissions cannot make writes fail: use a target that is a directory,
// an unsupported extension, a missing directory, and the injection hook (ENOSPC at sync).
#include <cerrno>
#include <cstdio>

#include <gtest/gtest.h>

#include "host/image/image_io.h"
#include "host/util/error.h"
#include "temp_dir.h"

namespace gc {
namespace {

class AtomicWrite : public test::TempDirTest {
protected:
    static Film solid(float v)
    {
        Film f(4, 4);
        f.fill({v, v, v, 1});
        return f;
    }
};

TEST_F(AtomicWrite, ReplacesTheFileAndLeavesNoTemp)
{
    write_image(path("out.pfm"), solid(1), {});
    write_image(path("out.pfm"), solid(2), {});
    EXPECT_EQ(read_image(path("out.pfm")).at(3, 3).r, 2.0f);
    EXPECT_EQ(file_count(), 1u);
}

TEST_F(AtomicWrite, InjectedNoSpaceKeepsThePreviousFile)
{
    write_image(path("out.pfm"), solid(1), {});
    const std::string before = slurp(path("out.pfm"));
    image_io_testing::fail_next_write(ENOSPC);
    try {
        write_image(path("out.pfm"), solid(2), {});
        FAIL() << "the injected failure did not throw";
    } catch (const OutputError& e) {
        const std::string msg = e.what();
        std::printf("message: %s\n", msg.c_str());
        EXPECT_NE(msg.find("out.pfm"), std::string::npos) << msg;
        EXPECT_NE(msg.find("No space left on device"), std::string::npos) << msg;
        EXPECT_EQ(e.code(), ExitCode::Output);
    }
    EXPECT_EQ(slurp(path("out.pfm")), before) << "the old image must survive a failed write";
    EXPECT_EQ(file_count(), 1u) << "the temp file must be removed";
    // The hook fires once: the next write succeeds.
    write_image(path("out.pfm"), solid(3), {});
    EXPECT_EQ(read_image(path("out.pfm")).at(0, 0).r, 3.0f);
}

#ifdef GC_HAVE_OIIO
TEST_F(AtomicWrite, InjectedFailureOnTheOiioPathToo)
{
    write_image(path("out.exr"), solid(1), {});
    const std::string before = slurp(path("out.exr"));
    image_io_testing::fail_next_write(EIO);
    EXPECT_THROW(write_image(path("out.exr"), solid(2), {}), OutputError);
    EXPECT_EQ(slurp(path("out.exr")), before);
    EXPECT_EQ(file_count(), 1u);
}
#endif

TEST_F(AtomicWrite, TargetIsADirectoryFailsAtRenameAndCleansUp)
{
    // A non-empty directory named like the output: rename(2) refuses to replace it.
    std::filesystem::create_directories(path("out.pfm") / "keep");
    try {
        write_image(path("out.pfm"), solid(1), {});
        FAIL() << "writing over a directory succeeded";
    } catch (const OutputError& e) {
        std::printf("message: %s\n", e.what());
        EXPECT_NE(std::string(e.what()).find("out.pfm"), std::string::npos);
    }
    EXPECT_TRUE(std::filesystem::is_directory(path("out.pfm") / "keep"));
    EXPECT_EQ(file_count(), 1u) << "the temp file must be removed";
}

TEST_F(AtomicWrite, MissingDirectoryNamesTheErrno)
{
    try {
        write_image(path("nodir/out.pfm"), solid(1), {});
        FAIL() << "writing into a missing directory succeeded";
    } catch (const OutputError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("nodir/out.pfm"), std::string::npos) << msg;
        EXPECT_NE(msg.find("No such file or directory"), std::string::npos) << msg;
    }
}

TEST_F(AtomicWrite, UnsupportedExtensionWritesNothing)
{
    write_image(path("keep.pfm"), solid(1), {});
    EXPECT_THROW(write_image(path("out.notaformat"), solid(1), {}), OutputError);
    EXPECT_THROW(write_image(path("keep.pfm"), Film(), {}), OutputError) << "an empty film is refused";
    EXPECT_EQ(read_image(path("keep.pfm")).at(0, 0).r, 1.0f);
    EXPECT_EQ(file_count(), 1u);
}

}  // namespace
}  // namespace gc
