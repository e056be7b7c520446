// The cross-check's id and depth figures and its edge rule, on hand-made images (no device).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "gc_aov.h"
#include "host/render/scene_convert.h"
#include "host/util/error.h"
#include "host/vk/agreement.h"

namespace gc::vk {
namespace {

// One triangle covering the lower-left half of the view: seen from (0,0,1) down -Z with a
// 90-degree field of view, the plane z = 0 spans [-1,1]^2 exactly, so the triangle's
// hypotenuse runs along the image diagonal x = y from the top-left corner to the
// bottom-right one (pixel units, y down).
Scene half_plane_scene()
{
    Scene s;
    s.positions = {Point3(-1, -1, 0), Point3(1, -1, 0), Point3(-1, 1, 0)};
    s.normals = {Normal3(0, 0, 1), Normal3(0, 0, 1), Normal3(0, 0, 1)};
    s.material_ids = {0};
    s.has_vertex_normals = {0};
    s.materials.resize(1);
    return s;
}

dev::GcCamera half_plane_camera(std::uint32_t size)
{
    Camera c;
    c.look_from = Point3(0, 0, 1);
    c.look_at = Point3(0, 0, 0);
    c.up = Vec3(0, 1, 0);
    c.vfov_degrees = 90.0f;
    return make_camera(c, static_cast<int>(size), static_cast<int>(size));
}

TEST(ProjectTriangle, InvertsTheCameraRays)
{
    const Scene s = half_plane_scene();
    double xy[3][2];
    ASSERT_TRUE(project_triangle(s, half_plane_camera(8), 8, 8, 0, xy));
    EXPECT_NEAR(xy[0][0], 0.0, 1e-5);  // (-1,-1) -> bottom left
    EXPECT_NEAR(xy[0][1], 8.0, 1e-5);
    EXPECT_NEAR(xy[1][0], 8.0, 1e-5);  // (1,-1) -> bottom right
    EXPECT_NEAR(xy[1][1], 8.0, 1e-5);
    EXPECT_NEAR(xy[2][0], 0.0, 1e-5);  // (-1,1) -> top left
    EXPECT_NEAR(xy[2][1], 0.0, 1e-5);
}

TEST(ProjectTriangle, RejectsCornersBehindTheCamera)
{
    Scene s = half_plane_scene();
    s.positions[1] = Point3(1, -1, 2); // behind the eye at z = 1
    double xy[3][2];
    EXPECT_FALSE(project_triangle(s, half_plane_camera(8), 8, 8, 0, xy));
}

// Ray-cast ids of the half-plane scene: pixel centres with y >= x are inside (the
// diagonal ones lie exactly on the hypotenuse).
std::vector<std::int32_t> half_plane_ids(std::uint32_t size)
{
    std::vector<std::int32_t> ids(size * size, -1);
    for (std::uint32_t y = 0; y < size; ++y)
        for (std::uint32_t x = 0; x < size; ++x)
            if (y >= x) ids[y * size + x] = 0;
    return ids;
}

TEST(EdgeRule, FlagsExactlyThePixelCentresOnAnEdge)
{
    const std::uint32_t n = 8;
    const Scene s = half_plane_scene();
    const std::vector<std::int32_t> ids = half_plane_ids(n);
    const std::vector<std::uint8_t> edge = edge_pixels(s, half_plane_camera(n), ids, ids, n, n);
    std::size_t flagged = 0;
    for (std::uint32_t y = 0; y < n; ++y)
        for (std::uint32_t x = 0; x < n; ++x) {
            // Centres on the diagonal are at distance 0 from the hypotenuse; every other
            // centre is at least 1/sqrt(2) pixel from it, and 1/2 pixel from the borders.
            EXPECT_EQ(edge[y * n + x], x == y ? 1 : 0) << "pixel " << x << "," << y;
            flagged += edge[y * n + x];
        }
    EXPECT_EQ(flagged, n);
}

TEST(EdgeRule, ATriangleOnlyTheTestImageShowsCountsToo)
{
    const std::uint32_t n = 8;
    const Scene s = half_plane_scene();
    const std::vector<std::int32_t> ref(n * n, -1); // the reference sees nothing
    const std::vector<std::int32_t> test = half_plane_ids(n);
    const std::vector<std::uint8_t> edge = edge_pixels(s, half_plane_camera(n), ref, test, n, n);
    EXPECT_EQ(edge[5 * n + 5], 1); // on the hypotenuse
    EXPECT_EQ(edge[5 * n + 2], 0); // inside: a real disagreement
    EXPECT_EQ(edge[2 * n + 5], 0); // outside, in neither image
}

TEST(EdgeRule, ThresholdIsInPixels)
{
    const std::uint32_t n = 8;
    const Scene s = half_plane_scene();
    const std::vector<std::int32_t> ids = half_plane_ids(n);
    // Pixel (2,3) is 1/sqrt(2) = 0.707 px from the hypotenuse (and 2.5 px from the left side).
    EXPECT_EQ(edge_pixels(s, half_plane_camera(n), ids, ids, n, n, 0.70)[3 * n + 2], 0);
    EXPECT_EQ(edge_pixels(s, half_plane_camera(n), ids, ids, n, n, 0.71)[3 * n + 2], 1);
}

TEST(CompareIds, CountsInteriorMismatchesAndSkipsExcludedPixels)
{
    const std::vector<std::int32_t> ref = {-1, 0, 0, 1};
    std::vector<std::int32_t> test = {-1, 0, 2, 1};
    const std::vector<float> depth = {0.0f, 2.0f, 2.0f, 4.0f};
    std::vector<float> test_depth = {0.0f, 2.0002f, 2.0f, 4.0f};
    IdDepthAgreement a = compare_ids_depth(ref, depth, test, test_depth, {});
    EXPECT_EQ(a.covered, 3u);
    EXPECT_EQ(a.compared, 3u);
    EXPECT_EQ(a.equal_ids, 2u);
    EXPECT_NEAR(a.id_agreement, 2.0 / 3.0, 1e-12);
    EXPECT_NEAR(a.max_depth_rel_error, 1e-4, 1e-7);

    a = compare_ids_depth(ref, depth, test, test_depth, {0, 0, 1, 0});
    EXPECT_EQ(a.edge_excluded, 1u);
    EXPECT_EQ(a.compared, 2u);
    EXPECT_DOUBLE_EQ(a.id_agreement, 1.0);
    EXPECT_THROW(compare_ids_depth(ref, depth, test, {1.0f}, {}), InputError);
}

TEST(AovFilms, IdsAndDepthComeFromTheRedChannel)
{
    Film f(2, 1);
    f.set(0, 0, Rgba{-1.0f, -1.0f, -1.0f, 1.0f});
    f.set(1, 0, Rgba{69325.0f, 69325.0f, 69325.0f, 1.0f});
    EXPECT_EQ(ids_from_film(f), (std::vector<std::int32_t>{-1, 69325}));
    EXPECT_EQ(depth_from_film(f), (std::vector<float>{-1.0f, 69325.0f}));
}

// The shared AOV header compiles as C++ too and computes the preview the raster pass shows.
TEST(SharedAovHeader, PreviewIsAlbedoUnderAHeadlightPlusClampedEmission)
{
    using namespace gc::dev;
    const float3 v = gc_aov_preview(make_float3(0.5f, 0.25f, 1.0f), make_float3(0, 0, 1), make_float3(0, 0, -1),
                                    make_float3(2.0f, 0.0f, 0.5f));
    EXPECT_FLOAT_EQ(v.x, 0.5f + 1.0f);
    EXPECT_FLOAT_EQ(v.y, 0.25f);
    EXPECT_FLOAT_EQ(v.z, 1.0f + 0.5f);
}

}  // namespace
}  // namespace gc::vk
