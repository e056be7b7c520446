// A render from a scene file to a film, as the CLI runs it and as other front ends (Python,
// the multi-device scheduler) build on it: load the scene, resolve the camera and build the
// BVH (prepare_scene), upload them to a device and compile the integrator (Session), then
// render with a deadline and cancellation (Session::render).
//
//     PreparedScene prepared = prepare_scene({"scene.glb"});
//     Session session(cl::select_device("any"), prepared, settings);
//     prepared = {};  // the device has its own copy
//     RenderOutcome outcome = session.render({.time_limit_seconds = 60});
//     write_image("out.exr", session.renderer().film(), meta);
#pragma once

#include <filesystem>
#include <memory>

#include "host/bvh/bvh.h"
#include "host/bvh/instance_bvh.h"
#include "host/cl/context.h"
#include "host/cl/device.h"
#include "host/render/device_scene.h"
#include "host/render/render_loop.h"
#include "host/render/render_setup.h"
#include "host/render/renderer.h"
#include "host/scene/camera_framing.h"
#include "host/scene/load_options.h"
#include "host/scene/scene.h"

namespace gc {

// A scene file and how to look at it.
struct SceneRequest {
    std::filesystem::path path;
    LoadOptions load;
    CameraOverrides camera;  // unset fields: the file's camera, or the framing of resolve_camera
    // A glTF whose nodes draw some mesh more than once stays instanced
    // (PreparedScene::instances), each mesh once on the device (every integrator traces the
    // two-level BVH).
    bool keep_instances = false;
};

// An instanced scene on the host and its two-level BVH's parts.
struct PreparedInstances {
    InstancedScene scene;
    InstanceBvhParts bvh;
};

// A scene on the host, ready for devices. An instanced scene (SceneRequest::keep_instances)
// has `instances`; then `scene` is its meshes in object space (materials, textures, lights
// and file as loaded) and `bvh` is empty.
struct PreparedScene {
    Scene scene;
    Camera camera;
    FlatBvh bvh;
    std::shared_ptr<const PreparedInstances> instances;
};

// Loads the scene (InputError naming the file on bad input) and resolves the camera.
PreparedScene load_with_camera(const SceneRequest& request);
// ... and builds the BVH.
PreparedScene prepare_scene(const SceneRequest& request);

class Session {
public:
    // Uploads `prepared` and the environment map settings.env_map_path names to `device`,
    // and builds the integrator's program. The session keeps nothing of `prepared`.
    Session(const cl::DeviceInfo& device, const PreparedScene& prepared, const RenderSettings& settings,
            const RenderSetup& setup = {});
    // The renderer holds the context by reference.
    Session(const Session&) = delete;
    Session& operator=(const Session&) = delete;

    // Renders until the film holds settings.spp samples, or `control` stops it.
    RenderOutcome render(const RenderControl& control = {});

    const cl::DeviceInfo& device() const { return m_context.device(); }
    const cl::Context& context() const { return m_context; }
    Renderer& renderer() { return m_renderer; }
    const Renderer& renderer() const { return m_renderer; }
    // The scene on the device, for material updates (DeviceScene::update_materials).
    DeviceScene& device_scene() { return *m_scene; }

private:
    cl::Context m_context;
    std::shared_ptr<DeviceScene> m_scene;
    Renderer m_renderer;
};

}  // namespace gc
