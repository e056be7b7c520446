// The project's EXR writer, read back by OpenImageIO (an independent reader): a single-part
// file of UINT and FLOAT channels, and a multi-part file whose parts keep their names, order,
// channels and values, also when one named part is alone.
#include <cstring>
#include <filesystem>

#include <gtest/gtest.h>

#include "host/image/exr_writer.h"
#include "host/util/error.h"
#include "temp_dir.h"

#if defined(GC_HAVE_OIIO)
#include <OpenImageIO/imageio.h>
#endif

namespace gc {
namespace {

ExrPart part(const std::string& name, float base)
{
    ExrPart p;
    p.name = name;
    p.channels.push_back({"Z", ExrPixelType::Float, float_bits({base, base + 1, base + 2, base + 3, base + 4, base + 5})});
    p.channels.push_back({"id", ExrPixelType::Uint, {7, 8, 9, 10, 11, 0xffffffffu}});
    p.text = {{"geocold:what", name}};
    return p;
}

TEST(ExrWriter, RefusesBadParts)
{
    EXPECT_THROW(encode_exr(3, 2, {}), UsageError);
    ExrPart wrong = part("a", 0);
    wrong.channels[0].bits.pop_back();
    EXPECT_THROW(encode_exr(3, 2, {wrong}), UsageError);
    EXPECT_THROW(encode_exr(3, 2, {part("a", 0), part("a", 1)}), UsageError);
    EXPECT_THROW(encode_exr(3, 2, {part("a", 0), part("", 1)}), UsageError);
}

#if defined(GC_HAVE_OIIO)
class ExrWriterFile : public test::TempDirTest {};

TEST_F(ExrWriterFile, OpenImageIOReadsEveryPartBack)
{
    for (const std::vector<ExrPart>& parts : {std::vector<ExrPart>{part("", 0.5f)}, std::vector<ExrPart>{part("alone", 1)},
                                              std::vector<ExrPart>{part("first", 2), part("second", 3)}}) {
        const std::filesystem::path path = this->path("parts.exr");
        write_exr(path, 3, 2, parts);
        auto in = OIIO::ImageInput::open(path.string());
        ASSERT_TRUE(in) << OIIO::geterror();
        for (std::size_t p = 0; p < parts.size(); ++p) {
            ASSERT_TRUE(in->seek_subimage(int(p), 0));
            const OIIO::ImageSpec& spec = in->spec();
            std::printf("  part %zu of %zu: '%s' %dx%d\n", p, parts.size(),
                        spec.get_string_attribute("oiio:subimagename").c_str(), spec.width, spec.height);
            EXPECT_EQ(spec.get_string_attribute("oiio:subimagename"), parts[p].name);
            EXPECT_EQ(spec.get_string_attribute("geocold:what"), parts[p].name);
            EXPECT_EQ(spec.width, 3);
            EXPECT_EQ(spec.height, 2);
            ASSERT_EQ(spec.channelnames, (std::vector<std::string>{"Z", "id"}));
            std::vector<float> z(6);
            std::vector<std::uint32_t> id(6);
            ASSERT_TRUE(in->read_image(int(p), 0, 0, 1, OIIO::TypeDesc::FLOAT, z.data()));
            ASSERT_TRUE(in->read_image(int(p), 0, 1, 2, OIIO::TypeDesc::UINT32, id.data()));
            EXPECT_EQ(float_bits(z), parts[p].channels[0].bits);
            EXPECT_EQ(id, parts[p].channels[1].bits);
        }
        EXPECT_FALSE(in->seek_subimage(int(parts.size()), 0));
    }
}
#endif

}  // namespace
}  // namespace gc
