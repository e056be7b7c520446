#include "host/scene/camera_framing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "host/util/error.h"

namespace gc {

namespace {

constexpr float k_default_fov_degrees = 40.0f;
// The box's projection may use 1 / k_margin of the half-field: a thin border of background.
constexpr double k_margin = 1.05;
constexpr double k_pi = 3.14159265358979323846;

std::string g3(double value)
{
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", value);
    return text;
}

Point3 to_float(const glm::dvec3& p)
{
    return {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)};
}

// How far from the box's centre, along +Z, the camera must stand for every corner of the box
// to project inside the (square, or wider) view: corner (dx, dy, dz) relative to the centre is
// inside when max(|dx|, |dy|) <= tan_half * (d - dz) / k_margin.
double framing_distance(const glm::dvec3& half_extent)
{
    const double tan_half = std::tan(0.5 * k_default_fov_degrees * k_pi / 180.0);
    const double lateral = std::max(half_extent.x, half_extent.y);
    if (lateral > 0.0) return half_extent.z + k_margin * lateral / tan_half;
    // A point, or a segment along the view axis: no width to fit, only its depth to clear.
    return half_extent.z > 0.0 ? 2.0 * half_extent.z : 1.0;
}

// Why no single-precision camera frames the box: too far (past float's range) or too close
// (the distance vanishes in the rounding of the centre's coordinates).
[[noreturn]] void throw_unframeable(const Scene& scene, const glm::dvec3& center, const glm::dvec3& extent,
                                    double dist)
{
    const std::string what = scene.name_for_messages() + ": scene extent " + g3(extent.x) + " x " + g3(extent.y) +
                             " x " + g3(extent.z);
    if (!std::isfinite(static_cast<float>(center.z + dist)))
        throw InputError(what + " is too large to frame: the default camera would stand at z = " +
                         g3(center.z + dist) + ", past single precision's range (" +
                         g3(std::numeric_limits<float>::max()) + ")");
    throw InputError(what + " around (" + g3(center.x) + ", " + g3(center.y) + ", " + g3(center.z) +
                     ") is too small to frame: the default camera, " + g3(dist) +
                     " from its centre, rounds onto the centre in single precision");
}

}  // namespace

// Looks down -Z at the centre of the bounds, from the nearest distance at which every corner
// of the bounding box projects inside the view. Fitting the corners rather than the bounding
// sphere frames boxy scenes (a Cornell box, a room) the way a person would: the open side
// fills the image instead of floating in a black border. Computed in double and rounded once,
// so that a scene near float's limits (a float extent overflows past 1.7e38) still frames
// wherever the camera's own position fits in a float.
Camera frame_camera(const Scene& scene) { return frame_camera(scene, scene.bounds()); }

Camera frame_camera(const Scene& scene, const Bounds3& b)
{
    Camera camera;
    camera.vfov_degrees = k_default_fov_degrees;
    if (b.empty()) return camera;
    const glm::dvec3 lo(b.lo.glm()), hi(b.hi.glm());
    const glm::dvec3 center = 0.5 * (lo + hi);
    const double dist = framing_distance(0.5 * (hi - lo));
    camera.look_at = to_float(center);
    camera.look_from = to_float(center + glm::dvec3(0.0, 0.0, dist));
    camera.up = Vec3(0.0f, 1.0f, 0.0f);
    if (!is_finite(camera.look_from) || camera.look_from == camera.look_at)
        throw_unframeable(scene, center, hi - lo, dist);
    return camera;
}

Camera resolve_camera(const Scene& scene, const CameraOverrides& overrides, const std::optional<Bounds3>& world_bounds)
{
    // A framed camera is only needed when the file has none and the user does not place one.
    const bool user_places_camera = overrides.look_from && overrides.look_at;
    Camera camera;  // the defaults (a 40-degree view) under a camera the user places
    if (scene.camera) camera = *scene.camera;
    else if (!user_places_camera) camera = world_bounds ? frame_camera(scene, *world_bounds) : frame_camera(scene);
    if (overrides.look_from) camera.look_from = *overrides.look_from;
    if (overrides.look_at) camera.look_at = *overrides.look_at;
    if (overrides.up) camera.up = *overrides.up;
    if (overrides.fov) camera.vfov_degrees = *overrides.fov;
    if (overrides.aperture_radius) camera.aperture_radius = *overrides.aperture_radius;
    if (overrides.focus_distance) camera.focus_distance = *overrides.focus_distance;

    // Compared exactly and normalised in double, so that cameras at any scale float can hold
    // pass (a float length underflows for points closer than ~1e-19).
    if (!is_finite(camera.look_from) || !is_finite(camera.look_at) || !is_finite(camera.up))
        throw UsageError("camera: look-from, look-at and up must be finite");
    if (camera.look_from == camera.look_at) throw UsageError("camera: look-from and look-at are the same point");
    if (camera.up == Vec3(0.0f, 0.0f, 0.0f)) throw UsageError("camera: the up vector is zero");
    const Vec3 side = cross(unit_direction(camera.look_from, camera.look_at), unit_vector(camera.up));
    if (!(length(side) > 1e-6f)) throw UsageError("camera: the up vector is parallel to the view direction");
    if (!(camera.vfov_degrees > 0.0f && camera.vfov_degrees < 180.0f))
        throw UsageError("camera: field of view " + std::to_string(camera.vfov_degrees) + " degrees is outside (0, 180)");
    if (!(camera.aperture_radius >= 0.0f) || !std::isfinite(camera.aperture_radius))
        throw UsageError("camera: the aperture radius must be a finite number >= 0");
    if (!(camera.focus_distance >= 0.0f) || !std::isfinite(camera.focus_distance))
        throw UsageError("camera: the focus distance must be a finite number > 0 (0: the look-at point)");
    return camera;
}

}  // namespace gc
