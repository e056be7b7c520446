// Default framing and user overrides.
#include <cmath>

#include <gtest/gtest.h>

#include "host/scene/camera_framing.h"
#include "host/util/error.h"
#include "scene_test_util.h"

namespace gc {
namespace {

Scene box_scene(const Point3& lo, const Point3& hi)
{
    Scene s;
    s.positions = {lo, hi, Point3(lo.x, hi.y, lo.z)};
    s.normals.assign(3, Normal3(0, 0, 1));
    s.material_ids = {0};
    s.has_vertex_normals = {0};
    s.materials.emplace_back();
    return s;
}

constexpr float k_deg = 3.14159265f / 180.0f;

TEST(CameraFraming, WholeBoundsInView)
{
    const Scene s = box_scene(Point3(-3, 1, -2), Point3(5, 4, 0.5f));
    const Camera c = frame_camera(s);
    EXPECT_EQ(c.vfov_degrees, 40.0f);
    EXPECT_EQ(c.look_at, s.bounds().centroid());
    EXPECT_EQ(c.look_from.x, c.look_at.x);  // from +Z, looking down -Z
    EXPECT_EQ(c.look_from.y, c.look_at.y);
    EXPECT_GT(c.look_from.z, c.look_at.z);
    EXPECT_EQ(c.up, Vec3(0, 1, 0));

    const Vec3 w = normalize(c.look_at - c.look_from);
    const Vec3 u = normalize(cross(w, c.up));
    const Vec3 v = cross(u, w);
    const float tan_half = std::tan(0.5f * c.vfov_degrees * k_deg);
    const Bounds3 b = s.bounds();
    float worst = 0.0f;
    for (int i = 0; i < 8; ++i) {
        const Point3 p((i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y, (i & 4) ? b.hi.z : b.lo.z);
        const Vec3 d = p - c.look_from;
        const float depth = dot(d, w);
        ASSERT_GT(depth, 0.0f);
        // Square image: both axes use the vertical half-angle.
        worst = std::fmax(worst, std::fmax(std::fabs(dot(d, u)), std::fabs(dot(d, v))) / (depth * tan_half));
    }
    std::printf("  farthest corner at %.3f of the half-field (must be <= 1)\n", worst);
    EXPECT_LE(worst, 1.0f);
    EXPECT_GT(worst, 0.5f);  // and not absurdly far away
}

TEST(CameraFraming, FileCameraAndOverrides)
{
    Scene s = box_scene(Point3(0, 0, 0), Point3(1, 1, 1));
    Camera file;
    file.look_from = Point3(0, 1, 3.5f);
    file.look_at = Point3(0, 1, 0);
    file.vfov_degrees = 39.3f;
    s.camera = file;

    const Camera same = resolve_camera(s, {});
    EXPECT_EQ(same.look_from, file.look_from);
    EXPECT_EQ(same.vfov_degrees, 39.3f);

    CameraOverrides o;
    o.look_from = Point3(2, 2, 2);
    o.fov = 60.0f;
    const Camera c = resolve_camera(s, o);
    EXPECT_EQ(c.look_from, Point3(2, 2, 2));
    EXPECT_EQ(c.look_at, file.look_at);
    EXPECT_EQ(c.vfov_degrees, 60.0f);

    s.camera.reset();
    CameraOverrides up;
    up.up = Vec3(1, 0, 0);
    const Camera framed = resolve_camera(s, up);
    EXPECT_EQ(framed.up, Vec3(1, 0, 0));
    EXPECT_EQ(framed.look_at, s.bounds().centroid());
}

TEST(CameraFraming, UnusableOverridesAreUsageErrors)
{
    const Scene s = box_scene(Point3(0, 0, 0), Point3(1, 1, 1));
    CameraOverrides same_point;
    same_point.look_from = Point3(1, 1, 1);
    same_point.look_at = Point3(1, 1, 1);
    EXPECT_THROW(resolve_camera(s, same_point), UsageError);
    CameraOverrides parallel;
    parallel.up = Vec3(0, 0, -2);  // the framed camera looks down -Z
    EXPECT_THROW(resolve_camera(s, parallel), UsageError);
    CameraOverrides fov;
    fov.fov = 180.0f;
    EXPECT_THROW(resolve_camera(s, fov), UsageError);
}

// The same box at every scale float holds frames the same way: the camera's distance is
// the same multiple of the extent, and resolve_camera accepts it (it used to call the look-
// from and look-at "the same point" below ~1e-19, when float's squared length underflowed).
TEST(CameraFraming, AnyRepresentableScale)
{
    const Scene unit = box_scene(Point3(-1, 0, -1), Point3(1, 2, 1));
    const Camera reference = frame_camera(unit);
    const float reference_ratio = (reference.look_from.z - reference.look_at.z) / 2.0f;
    for (const float scale : {1e-38f, 1e-30f, 1e-20f, 1e-12f, 1e-3f, 1e3f, 1e12f, 1e20f, 1e30f, 1e37f}) {
        const Scene s = box_scene(Point3(-scale, 0, -scale), Point3(scale, 2 * scale, scale));
        const Camera c = resolve_camera(s, {});
        EXPECT_TRUE(is_finite(c.look_from)) << scale;
        EXPECT_NE(c.look_from, c.look_at) << scale;
        EXPECT_EQ(c.look_at, Point3(0, scale, 0)) << scale;
        const double ratio = (double(c.look_from.z) - c.look_at.z) / (2.0 * scale);
        EXPECT_NEAR(ratio, reference_ratio, 1e-5 * reference_ratio) << scale;
    }
}

TEST(CameraFraming, UnframeableSceneIsAnInputError)
{
    // 1e-3 across at z = 1e7, where float's spacing is 1: the camera's 0.0014 vanishes.
    Scene tiny = box_scene(Point3(0, 0, 1e7f), Point3(1e-3f, 1e-3f, 1e7f));
    tiny.source_path = "tiny.obj";
    test::expect_input_error([&] { frame_camera(tiny); },
                             {"tiny.obj: scene extent 0.001 x 0.001 x 0", "too small to frame"});
    // 4e38 across: the camera would stand past float's largest value.
    Scene huge = box_scene(Point3(-2e38f, -2e38f, -2e38f), Point3(2e38f, 2e38f, 2e38f));
    huge.source_path = "huge.obj";
    const std::string msg = test::expect_input_error([&] { resolve_camera(huge, {}); },
                                                     {"huge.obj: scene extent 4e+38 x 4e+38 x 4e+38", "too large to frame"});
    EXPECT_EQ(msg.find("same point"), std::string::npos);

    // Nothing to frame when the file or the user places the camera.
    CameraOverrides placed;
    placed.look_from = Point3(0, 0, 1e7f + 8.0f);
    placed.look_at = Point3(0, 0, 1e7f);
    const Camera user = resolve_camera(tiny, placed);
    EXPECT_EQ(user.look_from, *placed.look_from);
    EXPECT_EQ(user.vfov_degrees, 40.0f);
    Camera file;
    file.look_from = Point3(0, 0, 3);
    huge.camera = file;
    EXPECT_EQ(resolve_camera(huge, {}).look_from, file.look_from);
}

TEST(CameraFraming, EmptySceneGivesDefault)
{
    const Camera c = frame_camera(Scene{});
    EXPECT_EQ(c.look_from, Point3(0, 0, 1));
    EXPECT_EQ(c.vfov_degrees, 40.0f);
}

}  // namespace
}  // namespace gc
