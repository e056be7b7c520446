// Options that change how a scene file is turned into a Scene.
#pragma once

namespace gc {

struct LoadOptions {
    int gltf_scene = -1; // glTF scene index; -1 = the file's default scene (else scene 0)
    // OBJ illum 2 with Ks > 0 becomes MaterialType::Phong (kd + ks clamped to <= 1). With this
    // set it stays Lambert with the file's Kd untouched, as the Mitsuba references treat it.
    bool phong_as_lambert = false;
};

}  // namespace gc
