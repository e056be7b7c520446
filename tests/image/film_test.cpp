#include <gtest/gtest.h>

#include "host/image/film.h"
#include "host/util/error.h"

namespace gc {
namespace {

TEST(Film, StartsBlackAndOpaque)
{
    const Film f(3, 2);
    EXPECT_EQ(f.width(), 3u);
    EXPECT_EQ(f.height(), 2u);
    EXPECT_EQ(f.data().size(), 3u * 2u * 4u);
    EXPECT_EQ(f.at(2, 1), (Rgba{0, 0, 0, 1}));
    EXPECT_FALSE(f.empty());
    EXPECT_TRUE(Film().empty());
}

TEST(Film, PixelAccessIsRowMajorTopFirst)
{
    Film f(4, 3);
    f.set(1, 2, {0.1f, 0.2f, 0.3f, 0.4f});
    EXPECT_EQ(f.at(1, 2), (Rgba{0.1f, 0.2f, 0.3f, 0.4f}));
    // Row 2, column 1 -> float index (2 * 4 + 1) * 4.
    EXPECT_EQ(f.data()[(2 * 4 + 1) * 4 + 2], 0.3f);
    EXPECT_EQ(f.pixel(1, 2), f.data().data() + (2 * 4 + 1) * 4);
    f.fill({1, 2, 3, 4});
    EXPECT_EQ(f.at(0, 0), (Rgba{1, 2, 3, 4}));
    EXPECT_EQ(f.at(3, 2), (Rgba{1, 2, 3, 4}));
}

TEST(Film, ImpossibleSizeIsAnInputError)
{
    EXPECT_THROW(Film(0xffffffffu, 0xffffffffu), InputError);
}

}  // namespace
}  // namespace gc
