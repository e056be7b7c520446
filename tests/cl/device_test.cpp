#include "host/cl/device.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <string>

#include "cl_test_util.h"

namespace gc::cl {
namespace {

using test::DeviceTest;

std::string lower(std::string s)
{
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

TEST_F(DeviceTest, ListFindsDevicesAndPrintsTable)
{
    ASSERT_GE(devices.size(), 1u);
    const std::string table = format_device_list(devices);
    std::printf("%s", table.c_str());
    for (const DeviceInfo& d : devices) {
        EXPECT_FALSE(d.device_name.empty());
        EXPECT_NE(table.find(d.device_name), std::string::npos);
        EXPECT_GT(d.compute_units, 0u);
        EXPECT_GT(d.max_alloc, 0u);
        EXPECT_LE(d.max_alloc, d.global_mem);
        EXPECT_GE(d.max_work_group_size, 1u);
        std::printf("  %s: %s, correctly rounded div/sqrt: %s\n", d.device_name.c_str(),
                    d.opencl_c_version.c_str(), d.correctly_rounded_div_sqrt ? "yes" : "no");
    }
    // One header line plus one line per device.
    EXPECT_EQ(static_cast<size_t>(std::count(table.begin(), table.end(), '\n')),
              devices.size() + 1);
}

TEST_F(DeviceTest, SelectBySpec)
{
    const DeviceInfo any = select_device("any", devices);
    const bool has_gpu =
        std::any_of(devices.begin(), devices.end(), [](const DeviceInfo& d) { return d.is_gpu; });
    EXPECT_EQ(any.is_gpu, has_gpu) << "any must prefer a GPU";
    EXPECT_EQ(select_device("ANY", devices).id, any.id);

    EXPECT_EQ(select_device("0", devices).id, devices[0].id);
    EXPECT_EQ(select_device(std::to_string(devices.size() - 1), devices).id, devices.back().id);

    for (const DeviceInfo& d : devices) {
        if (d.is_cpu) {
            EXPECT_TRUE(select_device("cpu", devices).is_cpu);
        }
        if (d.is_gpu) {
            EXPECT_TRUE(select_device("gpu", devices).is_gpu);
        }
    }
    // A middle piece of the name, in another case.
    const DeviceInfo& last = devices.back();
    const std::string piece = lower(last.device_name.substr(last.device_name.size() / 3, 4));
    const DeviceInfo by_name = select_device(piece, devices);
    std::printf("'%s' selects %s\n", piece.c_str(), by_name.device_name.c_str());
    EXPECT_NE(lower(by_name.device_name + by_name.vendor + by_name.platform_name).find(piece),
              std::string::npos);

    // The same through the listing entry point.
    EXPECT_EQ(select_device("0").device_name, devices[0].device_name);
}

TEST_F(DeviceTest, BadSpecListsDevices)
{
    for (const std::string spec : {"no-such-device-xyz", "99", ""}) {
        try {
            select_device(spec, devices);
            FAIL() << "no error for --device '" << spec << "'";
        } catch (const DeviceError& e) {
            const std::string message = e.what();
            std::printf("%s\n", message.c_str());
            EXPECT_NE(message.find("'" + spec + "'"), std::string::npos);
            EXPECT_NE(message.find("available devices"), std::string::npos);
            EXPECT_NE(message.find(devices[0].device_name), std::string::npos);
        }
    }
}

TEST(DeviceSelect, EmptyListIsAnError)
{
    EXPECT_THROW(select_device("any", {}), DeviceError);
    EXPECT_NE(format_device_list({}).find("no OpenCL devices"), std::string::npos);
}

}  // namespace
}  // namespace gc::cl
