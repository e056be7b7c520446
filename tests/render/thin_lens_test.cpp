// The thin-lens camera (gc_camera_sample, kernels/shared/gc_camera.h) on the host: a zero
// aperture is the pinhole bit for bit, and every ray of one film position, whatever its lens
// sample, leaves the aperture disk and passes through the same point of the plane in focus.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "gc_camera.h"
#include "gc_rng.h"
#include "host/render/scene_convert.h"

namespace gc {
namespace {

Camera thin_lens(float aperture, float focus)
{
    Camera c;
    c.look_from = Point3(1, 2, 5);
    c.look_at = Point3(0, 1, 0);
    c.vfov_degrees = 35.0f;
    c.aperture_radius = aperture;
    c.focus_distance = focus;
    return c;
}

glm::dvec3 xyz(const dev::float4& v) { return {v.x, v.y, v.z}; }

TEST(ThinLens, ZeroApertureIsThePinholeBitForBit)
{
    const dev::GcCamera cam = make_camera(thin_lens(0.0f, 3.0f), 64, 48);
    for (std::uint32_t s = 0; s < 64; ++s) {
        const dev::float4 u = dev::gc_rand4(s, s, GC_RNG_BLOCK_CAMERA, 1u);
        const dev::GcRay a = dev::gc_camera_sample(cam, 64, 48, s % 64, s % 48, u);
        const dev::GcRay b = dev::gc_camera_ray(cam, 64, 48, s % 64, s % 48, u.x, u.y);
        EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0) << "sample " << s;
    }
}

TEST(ThinLens, RaysOfOneFilmPointMeetOnThePlaneInFocus)
{
    const float aperture = 0.25f, focus = 3.0f;
    const dev::GcCamera cam = make_camera(thin_lens(aperture, focus), 64, 48);
    const glm::dvec3 origin = xyz(cam.origin), forward = glm::normalize(xyz(cam.forward));
    for (std::uint32_t px : {0u, 17u, 63u}) {
        glm::dvec3 first_hit(0.0);
        for (std::uint32_t s = 0; s < 32; ++s) {
            dev::float4 u = dev::gc_rand4(px, s, GC_RNG_BLOCK_CAMERA, 7u);
            u.x = 0.25f;  // one film position, many lens points
            u.y = 0.75f;
            const dev::GcRay ray = dev::gc_camera_sample(cam, 64, 48, px, 20, u);
            const glm::dvec3 o = xyz(ray.org_tmin), d = xyz(ray.dir_tmax);
            // The lens point: in the plane through the origin across the view axis, within the radius.
            EXPECT_NEAR(glm::dot(o - origin, forward), 0.0, 1e-5);
            EXPECT_LE(glm::length(o - origin), aperture * (1.0 + 1e-5));
            // Where the ray crosses the plane in focus.
            const double t = (focus - glm::dot(o - origin, forward)) / glm::dot(d, forward);
            const glm::dvec3 p = o + d * t;
            if (s == 0) first_hit = p;
            EXPECT_NEAR(glm::length(p - first_hit), 0.0, 1e-5) << "pixel " << px << ", sample " << s;
        }
    }
}

TEST(ThinLens, FocusDefaultsToTheLookAtPoint)
{
    const Camera c = thin_lens(0.1f, 0.0f);
    const dev::GcCamera cam = make_camera(c, 8, 8);
    EXPECT_NEAR(cam.forward.w, std::sqrt(1.0 + 1.0 + 25.0), 1e-5);
    EXPECT_EQ(cam.origin.w, 0.1f);
    EXPECT_EQ(make_camera(thin_lens(0.0f, 0.0f), 8, 8).forward.w, 0.0f);  // a pinhole keeps w = 0
}

}  // namespace
}  // namespace gc
