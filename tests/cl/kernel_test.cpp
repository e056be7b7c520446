#include "host/cl/kernel.h"

#include <gtest/gtest.h>

#include <string>
#include <tuple>
#include <vector>

#include "cl_test_util.h"
#include "host/cl/buffer.h"
#include "host/cl/program.h"
#include "test_kernels.h"

namespace gc::cl {
namespace {

class KernelTest : public test::DeviceTest {
protected:
    void SetUp() override
    {
        DeviceTest::SetUp();
        if (IsSkipped()) return;
        dir.write("compute.cl", test::compute_cl);
        program = std::make_unique<Program>(*context, "compute.cl", "",
                                            BuildConfig{dir.path(), {}, false});
    }
    test::TempKernelDir dir;
    std::unique_ptr<Program> program;
};

TEST_F(KernelTest, ArgCountMismatchIsAClearError)
{
    Kernel kernel = program->kernel("compute");
    EXPECT_EQ(kernel.num_args(), 3u);
    auto data = Buffer<float>::create(*context, 4, CL_MEM_READ_WRITE, "data");
    try {
        kernel.set_args(data, 4u);
        FAIL() << "no error for 2 of 3 arguments";
    } catch (const DeviceError& e) {
        std::printf("%s\n", e.what());
        EXPECT_STREQ(e.what(), "kernel 'compute' takes 3 arguments but set_args was given 2");
    }
    EXPECT_THROW(kernel.set_args(data, 4u, 1.0f, 2.0f), DeviceError);
    EXPECT_NO_THROW(kernel.set_args(data, 4u, 1.0f));
}

// A std::tuple passed to set_args (DeviceScene::bvh_args() and the like) stands for its
// elements, in order, nested groups included: the same launch with the arguments listed one
// by one must write the same bits, and the arity check counts the elements. Two kernel objects,
// so that the grouped launch cannot run on arguments left from the listed one.
TEST_F(KernelTest, TupleArgumentIsAGroupSetInOrder)
{
    Kernel listed = program->kernel("compute");
    Kernel kernel = program->kernel("compute");
    const cl_uint n = 4;
    const float k = 2.0f;
    std::vector<float> a(n, 0.0f), b(n, 0.0f);
    auto flat = Buffer<float>::create(*context, n, CL_MEM_READ_WRITE, "flat");
    auto grouped = Buffer<float>::create(*context, n, CL_MEM_READ_WRITE, "grouped");
    flat.write(a);
    grouped.write(b);
    listed.set_args(flat, n, k);
    listed.launch(*context, n);
    kernel.set_args(std::tie(grouped), std::make_tuple(std::make_tuple(n), k));
    kernel.launch(*context, n);
    flat.read(a);
    grouped.read(b);
    for (cl_uint i = 0; i < n; ++i) std::printf("data[%u]: listed %.9g, grouped %.9g\n", i, a[i], b[i]);
    EXPECT_EQ(a, b);
    try {
        kernel.set_args(std::tie(grouped), std::make_tuple(n));
        FAIL() << "no error for a group of 1 where 2 arguments remain";
    } catch (const DeviceError& e) {
        std::printf("%s\n", e.what());
        EXPECT_STREQ(e.what(), "kernel 'compute' takes 3 arguments but set_args was given 2");
    }
}

TEST_F(KernelTest, WrongArgSizeNamesTheArgument)
{
    Kernel kernel = program->kernel("compute");
    auto data = Buffer<float>::create(*context, 4, CL_MEM_READ_WRITE, "data");
    try {
        kernel.set_args(data, 4.0, 1.0f);  // a double where the kernel takes a uint
        FAIL() << "no error for an 8-byte value in a 4-byte argument";
    } catch (const ClError& e) {
        std::printf("%s\n", e.what());
        EXPECT_EQ(e.code(), CL_INVALID_ARG_SIZE);
        EXPECT_NE(std::string(e.what()).find("argument 1 of kernel 'compute'"), std::string::npos);
    }
}

TEST_F(KernelTest, LaunchRoundsUpAndKernelsBoundsCheck)
{
    Kernel kernel = program->kernel("count_items");
    auto hits = Buffer<cl_uint>::create(*context, 1, CL_MEM_READ_WRITE, "hits");
    for (const cl_uint n : {1u, 63u, 1000u, 4097u}) {
        std::vector<cl_uint> zero = {0u};
        hits.write(zero);
        kernel.set_args(hits, n);
        kernel.launch(*context, n, 0, "count");
        hits.read(zero);
        EXPECT_EQ(zero[0], n) << "local size " << context->default_local_size();
    }
    std::printf("default local size on %s: %zu (kernel max %zu)\n",
                context->device().device_name.c_str(), context->default_local_size(),
                kernel.max_work_group_size());
    EXPECT_NO_THROW(kernel.launch(*context, 0));  // empty launches are no-ops
    context->finish();
}

TEST_F(KernelTest, UnknownKernelNameIsNamed)
{
    try {
        program->kernel("no_such_kernel");
        FAIL() << "no error for a missing kernel";
    } catch (const ClError& e) {
        std::printf("%s\n", e.what());
        EXPECT_EQ(e.code(), CL_INVALID_KERNEL_NAME);
        EXPECT_NE(std::string(e.what()).find("'no_such_kernel' from 'compute.cl'"),
                  std::string::npos);
    }
}

}  // namespace
}  // namespace gc::cl
