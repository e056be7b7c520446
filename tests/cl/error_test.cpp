#include "host/cl/error.h"

#include <gtest/gtest.h>

#include <string>

namespace gc::cl {
namespace {

TEST(ClErrorName, KnownCodes)
{
    EXPECT_STREQ(cl_error_name(CL_SUCCESS), "CL_SUCCESS");
    EXPECT_STREQ(cl_error_name(-5), "CL_OUT_OF_RESOURCES");
    EXPECT_STREQ(cl_error_name(-11), "CL_BUILD_PROGRAM_FAILURE");
    EXPECT_STREQ(cl_error_name(-46), "CL_INVALID_KERNEL_NAME");
    EXPECT_STREQ(cl_error_name(-61), "CL_INVALID_BUFFER_SIZE");
    EXPECT_STREQ(cl_error_name(-68), "CL_INVALID_DEVICE_PARTITION_COUNT");
    EXPECT_STREQ(cl_error_name(-70), "CL_INVALID_DEVICE_QUEUE");
    EXPECT_STREQ(cl_error_name(-1001), "CL_PLATFORM_NOT_FOUND_KHR");
    EXPECT_STREQ(cl_error_name(12345), "unknown OpenCL error");
}

TEST(ClErrorName, EveryCoreCodeHasAName)
{
    // OpenCL 1.2 defines 0, -1..-19 and -30..-68 with no gaps.
    int named = 0;
    for (cl_int code = 0; code >= -68; --code) {
        if (code < -19 && code > -30) continue;
        EXPECT_STRNE(cl_error_name(code), "unknown OpenCL error") << code;
        named += std::string(cl_error_name(code)).rfind("CL_", 0) == 0;
    }
    std::printf("named core codes: %d\n", named);
    EXPECT_EQ(named, 20 + 39);
}

TEST(ClError, MessageNamesCallCodeAndContext)
{
    const ClError error("clCreateBuffer", CL_INVALID_BUFFER_SIZE,
                        "allocating 'bvh nodes' (3.2 GiB) on NVIDIA H100");
    EXPECT_STREQ(error.what(),
                 "clCreateBuffer failed: CL_INVALID_BUFFER_SIZE (-61) while allocating 'bvh nodes' "
                 "(3.2 GiB) on "
                 "NVIDIA H100");
    EXPECT_EQ(error.call(), "clCreateBuffer");
    EXPECT_EQ(error.code(), CL_INVALID_BUFFER_SIZE);
    EXPECT_STREQ(error.code_name(), "CL_INVALID_BUFFER_SIZE");
    EXPECT_EQ(error.gc::Error::code(), ExitCode::Device);
    EXPECT_STREQ(ClError("clFinish", CL_OUT_OF_RESOURCES, "").what(),
                 "clFinish failed: CL_OUT_OF_RESOURCES (-5)");
}

TEST(ClBuildError, MessageCarriesTheLog)
{
    const ClBuildError error(CL_BUILD_PROGRAM_FAILURE, "building 'x.cl' for pocl",
                             "x.cl:3:5: error: use of undeclared identifier 'y'");
    const std::string message = error.what();
    EXPECT_NE(
        message.find("clBuildProgram failed: CL_BUILD_PROGRAM_FAILURE (-11) while building 'x.cl'"),
        std::string::npos)
        << message;
    EXPECT_NE(message.find("x.cl:3:5: error: use of undeclared identifier 'y'"), std::string::npos)
        << message;
    EXPECT_EQ(error.log(), "x.cl:3:5: error: use of undeclared identifier 'y'");
}

cl_int fake_call(int, int)
{
    return CL_INVALID_VALUE;
}
cl_int fake_ok(int)
{
    return CL_SUCCESS;
}
int fake_create(int value, cl_int* err)
{
    *err = value < 0 ? CL_OUT_OF_HOST_MEMORY : CL_SUCCESS;
    return value * 2;
}

TEST(ClMacros, CheckAndCreate)
{
    EXPECT_NO_THROW(GC_CL(fake_ok, 1));
    try {
        GC_CL_WHAT("doing a test", fake_call, 1, 2);
        FAIL() << "GC_CL_WHAT did not throw";
    } catch (const ClError& e) {
        EXPECT_STREQ(e.what(), "fake_call failed: CL_INVALID_VALUE (-30) while doing a test");
    }
    EXPECT_THROW(GC_CL(fake_call, 1, 2), DeviceError);
    EXPECT_EQ(GC_CL_CREATE("creating", fake_create, 21), 42);
    try {
        (void)GC_CL_CREATE(std::string("creating 'thing'"), fake_create, -1);
        FAIL() << "GC_CL_CREATE did not throw";
    } catch (const ClError& e) {
        EXPECT_EQ(e.call(), "fake_create");
        EXPECT_EQ(e.context(), "creating 'thing'");
    }
}

TEST(FormatBytes, Units)
{
    EXPECT_EQ(format_bytes(0), "0 bytes");
    EXPECT_EQ(format_bytes(1), "1 byte");
    EXPECT_EQ(format_bytes(1023), "1023 bytes");
    EXPECT_EQ(format_bytes(1536), "1.5 KiB");
    EXPECT_EQ(format_bytes(3435973837ull), "3.2 GiB");
    EXPECT_EQ(format_bytes(80ull << 30), "80 GiB");
}

}  // namespace
}  // namespace gc::cl
