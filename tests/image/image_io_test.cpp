// Round trips through every format, metadata, and the reading/checking errors.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <vector>

#include <gtest/gtest.h>
#ifdef GC_HAVE_OIIO
#include <OpenImageIO/imageio.h>
#endif

#include "host/image/image_io.h"
#include "host/util/error.h"
#include "temp_dir.h"

namespace gc {
namespace {

using test::TempDirTest;

// A small image with values a writer could get wrong: negatives, > 1, tiny, non-dyadic.
Film test_pattern(uint32_t w = 5, uint32_t h = 3)
{
    Film f(w, h);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x)
            f.set(x, y, {0.1f * float(x) + 0.013f, float(y) * 1.7f, x == 0 ? -0.25f : 3e-5f * float(x + y), 0.5f + 0.1f * float(y)});
    return f;
}

ImageMetadata test_meta()
{
    return {"Test Device (OpenCL 3.0)", "path", "scenes/cornell-box/cornell.obj", 1024, 12.5, 4000000000u};
}

std::string error_of(auto&& fn)
{
    try {
        fn();
    } catch (const Error& e) {
        return e.what();
    }
    return "(no exception)";
}

class ImageIo : public TempDirTest {};

TEST_F(ImageIo, SrgbTransferFunctions)
{
    EXPECT_EQ(linear_to_srgb8(0.0f), 0);
    EXPECT_EQ(linear_to_srgb8(1.0f), 255);
    EXPECT_EQ(linear_to_srgb8(7.0f), 255);  // clamp
    EXPECT_EQ(linear_to_srgb8(-1.0f), 0);
    EXPECT_EQ(linear_to_srgb8(std::numeric_limits<float>::quiet_NaN()), 0);
    // Linear 0.5 is sRGB 0.7354 -> 188 (IEC 61966-2-1).
    std::printf("srgb8(0.5) = %d (want 188), srgb8(0.0031308) = %d\n", linear_to_srgb8(0.5f), linear_to_srgb8(0.0031308f));
    EXPECT_EQ(linear_to_srgb8(0.5f), 188);
    EXPECT_NEAR(srgb_encode(0.0031308f), 0.04045f, 1e-5f);  // the two pieces meet
    for (float v : {0.0f, 0.001f, 0.01f, 0.2f, 0.5f, 0.9f, 1.0f}) EXPECT_NEAR(srgb_decode(srgb_encode(v)), v, 1e-6f);
}

TEST_F(ImageIo, PfmRoundTripIsExactRgb)
{
    const Film f = test_pattern();
    write_image(path("a.pfm"), f, test_meta());
    const Film g = read_image(path("a.pfm"));
    ASSERT_EQ(g.width(), f.width());
    ASSERT_EQ(g.height(), f.height());
    for (uint32_t y = 0; y < f.height(); ++y)
        for (uint32_t x = 0; x < f.width(); ++x) {
            const Rgba a = f.at(x, y), b = g.at(x, y);
            EXPECT_EQ(a.r, b.r);
            EXPECT_EQ(a.g, b.g);
            EXPECT_EQ(a.b, b.b);
            EXPECT_EQ(b.a, 1.0f);  // PFM has no alpha
        }
}

TEST_F(ImageIo, PfmIsBottomToTopLittleEndian)
{
    Film f(1, 2);
    f.set(0, 0, {1, 1, 1, 1});  // top
    f.set(0, 1, {2, 2, 2, 1});  // bottom
    write_image(path("b.pfm"), f, {});
    const std::string bytes = slurp(path("b.pfm"));
    const std::string header = "PF\n1 2\n-1.0\n";
    ASSERT_EQ(bytes.substr(0, header.size()), header);
    ASSERT_EQ(bytes.size(), header.size() + 2 * 12);
    float first;
    std::memcpy(&first, bytes.data() + header.size(), 4);
    EXPECT_EQ(first, 2.0f) << "the first row in a PFM file is the bottom of the image";
}

TEST_F(ImageIo, PfmReadsBigEndianAndGrey)
{
    // "Pf" grey, positive scale = big-endian: one pixel, 0.5 = 0x3f000000.
    spit(path("g.pfm"), std::string("Pf\n1 1\n1.0\n") + std::string("\x3f\x00\x00\x00", 4));
    const Film g = read_image(path("g.pfm"));
    EXPECT_EQ(g.at(0, 0), (Rgba{0.5f, 0.5f, 0.5f, 1.0f}));
}

TEST_F(ImageIo, PpmRoundTripWithinQuantization)
{
    const Film f = test_pattern();
    write_image(path("a.ppm"), f, {});
    const std::string bytes = slurp(path("a.ppm"));
    EXPECT_EQ(bytes.substr(0, 11), "P6\n5 3\n255\n");
    const Film g = read_image(path("a.ppm"));
    double worst = 0;
    for (uint32_t y = 0; y < f.height(); ++y)
        for (uint32_t x = 0; x < f.width(); ++x) {
            const float* a = f.pixel(x, y);
            const float* b = g.pixel(x, y);
            for (int c = 0; c < 3; ++c) {
                const float want = srgb_decode(float(linear_to_srgb8(a[c])) / 255.0f);
                EXPECT_EQ(b[c], want);
                // Quantization error in encoded space is at most half a step.
                const float clamped = std::fmin(std::fmax(a[c], 0.0f), 1.0f);
                worst = std::fmax(worst, std::fabs(srgb_encode(b[c]) - srgb_encode(clamped)));
            }
        }
    std::printf("PPM round trip: worst encoded error %.5f (limit 0.5/255 = %.5f)\n", worst, 0.5 / 255);
    EXPECT_LE(worst, 0.5 / 255 + 1e-6);
}

TEST_F(ImageIo, MalformedFilesAreInputErrorsNamingTheFile)
{
    spit(path("trunc.pfm"), "PF\n4 4\n-1.0\n" + std::string(10, '\0'));
    const std::string e1 = error_of([&] { read_image(path("trunc.pfm")); });
    EXPECT_NE(e1.find("trunc.pfm"), std::string::npos) << e1;
    EXPECT_NE(e1.find("truncated"), std::string::npos) << e1;
    spit(path("bad.pfm"), "P5\n1 1\n255\n\x01");
    EXPECT_THROW(read_image(path("bad.pfm")), InputError);
    spit(path("neg.ppm"), "P6\n-3 1\n255\n");
    EXPECT_THROW(read_image(path("neg.ppm")), InputError);
    const std::string e2 = error_of([&] { read_image(path("missing.pfm")); });
    EXPECT_NE(e2.find("missing.pfm"), std::string::npos) << e2;
    EXPECT_NE(e2.find("No such file"), std::string::npos) << e2;
    EXPECT_THROW(read_image(path("missing.exr")), InputError);
}

TEST_F(ImageIo, CheckOutputPathAcceptsAWritableTarget)
{
    EXPECT_NO_THROW(check_output_path(path("ok.pfm")));
    EXPECT_FALSE(std::filesystem::exists(path("ok.pfm")));
    EXPECT_EQ(file_count(), 0u) << "the probe file must not be left behind";
}

TEST_F(ImageIo, CheckOutputPathErrors)
{
    const std::string missing = error_of([&] { check_output_path(path("no/such/dir/out.pfm")); });
    std::printf("missing dir: %s\n", missing.c_str());
    EXPECT_NE(missing.find("does not exist"), std::string::npos) << missing;

    std::filesystem::create_directory(path("adir.pfm"));
    const std::string isdir = error_of([&] { check_output_path(path("adir.pfm")); });
    EXPECT_NE(isdir.find("is a directory"), std::string::npos) << isdir;

    spit(path("plainfile"), "x");
    const std::string notdir = error_of([&] { check_output_path(path("plainfile/out.pfm")); });
    EXPECT_NE(notdir.find("not a directory"), std::string::npos) << notdir;

    const std::string noext = error_of([&] { check_output_path(path("out")); });
    EXPECT_NE(noext.find("no extension"), std::string::npos) << noext;

    const std::string badext = error_of([&] { check_output_path(path("out.notaformat")); });
    std::printf("bad extension: %s\n", badext.c_str());
    EXPECT_NE(badext.find("out.notaformat"), std::string::npos) << badext;
    EXPECT_THROW(check_output_path(path("out.notaformat")), OutputError);
    if (!image_io_has_oiio()) {
        const std::string needs = error_of([&] { check_output_path(path("out.exr")); });
        EXPECT_NE(needs.find("OpenImageIO"), std::string::npos) << needs;
    }
}

// The built-in PNG writer needs no OIIO: the file starts with the PNG signature and IHDR
// (width, height, 8-bit RGB), holds the metadata as tEXt, and ends with IEND.
TEST_F(ImageIo, PngIsWrittenWithoutOiio)
{
    write_image(path("s.png"), test_pattern(7, 4), test_meta());
    std::FILE* file = std::fopen(path("s.png").c_str(), "rb");
    ASSERT_TRUE(file);
    std::string bytes;
    char buffer[4096];
    for (size_t n; (n = std::fread(buffer, 1, sizeof buffer, file)) > 0;) bytes.append(buffer, n);
    std::fclose(file);
    ASSERT_GT(bytes.size(), 33u);
    EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
    EXPECT_EQ(bytes.substr(12, 4), "IHDR");
    const std::string ihdr = bytes.substr(16, 13);
    EXPECT_EQ(ihdr.substr(0, 8), std::string("\0\0\0\x07\0\0\0\x04", 8)) << "width 7, height 4";
    EXPECT_EQ(ihdr[8], 8) << "bit depth";
    EXPECT_EQ(ihdr[9], 2) << "colour type RGB";
    EXPECT_NE(bytes.find(std::string("tEXtgeocold:device") + '\0' + "Test Device (OpenCL 3.0)"), std::string::npos);
    EXPECT_EQ(bytes.substr(bytes.size() - 8, 4), "IEND");
}

#ifdef GC_HAVE_OIIO
TEST_F(ImageIo, ExrRoundTripIsExactRgba)
{
    const Film f = test_pattern(7, 4);
    write_image(path("a.exr"), f, test_meta());
    const Film g = read_image(path("a.exr"));
    EXPECT_EQ(g, f) << "EXR stores 32-bit float RGBA losslessly";
}

TEST_F(ImageIo, ExrMetadataReadableThroughOiio)
{
    write_image(path("m.exr"), test_pattern(), test_meta());
    auto in = OIIO::ImageInput::open(path("m.exr").string());
    ASSERT_TRUE(in) << OIIO::geterror();
    const OIIO::ImageSpec& spec = in->spec();
    EXPECT_EQ(spec.get_string_attribute("geocold:device"), "Test Device (OpenCL 3.0)");
    EXPECT_EQ(spec.get_string_attribute("geocold:integrator"), "path");
    EXPECT_EQ(spec.get_string_attribute("geocold:scene"), "scenes/cornell-box/cornell.obj");
    EXPECT_EQ(spec.get_int_attribute("geocold:spp"), 1024);
    EXPECT_FLOAT_EQ(spec.get_float_attribute("geocold:seconds"), 12.5f);
    EXPECT_EQ(spec.get_string_attribute("geocold:seed"), "4000000000");
    const std::string sw = spec.get_string_attribute("Software");
    std::printf("Software = '%s'\n", sw.c_str());
    EXPECT_EQ(sw.rfind("geocold-cl ", 0), 0u) << sw;
    EXPECT_EQ(spec.nchannels, 4);
    EXPECT_EQ(spec.format, OIIO::TypeDesc::FLOAT);
}

TEST_F(ImageIo, PngIsSrgb8AndRoundTripsWithinQuantization)
{
    const Film f = test_pattern();
    write_image(path("a.png"), f, test_meta());
    {
        auto in = OIIO::ImageInput::open(path("a.png").string());
        ASSERT_TRUE(in);
        EXPECT_EQ(in->spec().format, OIIO::TypeDesc::UINT8);
        EXPECT_EQ(in->spec().nchannels, 3);
        std::vector<unsigned char> px(size_t(f.width()) * 3);  // one whole scanline
        ASSERT_TRUE(in->read_scanline(0, 0, OIIO::TypeDesc::UINT8, px.data()));
        // Pixel (0,0) is linear (0.013, 0, -0.25): encoded 0.013 -> 30, 0 -> 0, clamp -> 0.
        EXPECT_EQ(px[0], linear_to_srgb8(0.013f));
        EXPECT_EQ(px[2], 0);
    }
    const Film g = read_image(path("a.png"));
    for (uint32_t y = 0; y < f.height(); ++y)
        for (uint32_t x = 0; x < f.width(); ++x)
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(g.pixel(x, y)[c], srgb_decode(float(linear_to_srgb8(f.pixel(x, y)[c])) / 255.0f), 1e-6f);
}

// PNG is written built in (png_writer.cpp): OIIO (libpng) must read its metadata back.
TEST_F(ImageIo, PngMetadataReadableThroughOiio)
{
    write_image(path("m.png"), test_pattern(), test_meta());
    auto in = OIIO::ImageInput::open(path("m.png").string());
    ASSERT_TRUE(in) << OIIO::geterror();
    const OIIO::ImageSpec& spec = in->spec();
    EXPECT_EQ(spec.get_string_attribute("geocold:device"), "Test Device (OpenCL 3.0)");
    EXPECT_EQ(spec.get_string_attribute("geocold:integrator"), "path");
    EXPECT_EQ(spec.get_string_attribute("geocold:scene"), "scenes/cornell-box/cornell.obj");
    EXPECT_EQ(spec.get_string_attribute("geocold:spp"), "1024");
    EXPECT_EQ(spec.get_string_attribute("geocold:seed"), "4000000000");
    const std::string sw = spec.get_string_attribute("Software");
    const std::string cs = spec.get_string_attribute("oiio:ColorSpace");
    std::printf("Software = '%s', oiio:ColorSpace = '%s'\n", sw.c_str(), cs.c_str());
    EXPECT_EQ(sw.rfind("geocold-cl ", 0), 0u) << sw;
    EXPECT_EQ(cs, "sRGB");
}

TEST_F(ImageIo, HdrRoundTripIsClose)
{
    Film f(2, 2);
    f.fill({0.25f, 2.0f, 100.0f, 1.0f});
    write_image(path("a.hdr"), f, {});
    const Film g = read_image(path("a.hdr"));
    // RGBE keeps ~8 bits of mantissa per channel relative to the largest.
    EXPECT_NEAR(g.at(1, 1).b, 100.0f, 1.0f);
    EXPECT_NEAR(g.at(1, 1).g, 2.0f, 0.4f);
}
#else
TEST_F(ImageIo, WithoutOiioOtherFormatsSayWhy)
{
    const std::string e = error_of([&] { write_image(path("a.exr"), test_pattern(), {}); });
    EXPECT_NE(e.find("OpenImageIO"), std::string::npos) << e;
    EXPECT_EQ(file_count(), 0u);
}
#endif

}  // namespace
}  // namespace gc
