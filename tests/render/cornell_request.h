// A bundled Cornell box seen from the Mitsuba references' camera (tests/data/refs/cornell-*.json),
// for the render tests that load it through the session API.
#pragma once

#include <filesystem>

#include "host/render/session.h"

namespace gc::test {

inline SceneRequest cornell_request(const char* file = "CornellBox-Original.obj")
{
    SceneRequest request;
    request.path = std::filesystem::path(GC_TEST_SOURCE_DIR) / "scenes/cornell-box" / file;
    request.camera.look_from = Point3(0, 1, 3.9f);
    request.camera.look_at = Point3(0, 1, 0);
    request.camera.fov = 39.3077f;
    return request;
}

}  // namespace gc::test
