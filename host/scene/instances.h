// A scene of instances: meshes stored once in object space, each drawn any number of times
// through an affine transform. The device traces it with a two-level BVH
// (host/bvh/instance_bvh.h, kernels/shared/gc_instance.h); flatten_instances() spells it out
// as the plain Scene every other part of the renderer reads, which is also the reference the
// two-level traversal is tested against.
//
// Hits of the two agree bit for bit when every transform maps float coordinates to float
// coordinates exactly (signed axis permutations, power-of-two scales, translations the
// coordinates absorb without rounding): the ray's transform into object space and the
// vertices' into world space are then both exact, and the watertight test gives the same t,
// u and v in either space (gc_intersect.h). Other transforms round differently in the two
// spaces, so t agrees to a few ulps and a ray within rounding of a shared edge may take the
// neighbour.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "host/scene/scene.h"

namespace gc {

// Triangles [first_triangle, first_triangle + triangle_count) of InstancedScene::meshes.
struct MeshRange {
    std::uint32_t first_triangle = 0;
    std::uint32_t triangle_count = 0;
};

struct Instance {
    std::uint32_t mesh = 0;
    glm::mat4 object_to_world{1.0f}; // affine: the last row is (0, 0, 0, 1)
};

struct InstancedScene {
    // Every mesh's triangles in object space, mesh after mesh, with their materials and uvs;
    // also the scene's materials, textures, lights, camera and source path.
    Scene meshes;
    std::vector<MeshRange> mesh_ranges;
    std::vector<Instance> instances;

    std::size_t instanced_triangle_count() const;
};

// Throws InputError naming meshes.name_for_messages() when a mesh range leaves the triangle
// arrays or is empty, an instance names a mesh that does not exist, or a transform is not a
// finite, invertible affine map.
void validate_instances(const InstancedScene& scene);

// What a mirroring instance (negative determinant) does to its triangles' winding.
enum class MirroredWinding {
    // The object-space order, mirrored: the geometric normal from the winding turns to the
    // other side of the shading normals. Both spaces' hits then agree bit for bit under
    // exact transforms (the traversal tests' reference).
    AsTransformed,
    // Corners 1 and 2 swapped, bitangent signs flipped: the face the file calls front stays
    // front, as load_gltf does for mirrored nodes and the kernels do for instances
    // (gc_instance_attribs.h).
    FrontStaysFront,
};

// The world-space scene: instance after instance, each instance's triangles in mesh order, so
// triangle k of instance i is triangle first_flat(i) + k. Positions through object_to_world
// (float arithmetic, in the order (m0 x + m1 y) + m2 z + m3), normals through its inverse
// transpose, tangents through its linear part. Validates first; InputError naming the file
// when the flat scene would pass the limits of scene_checks.h (flat_triangles_fit).
Scene flatten_instances(const InstancedScene& scene, MirroredWinding winding = MirroredWinding::AsTransformed);

// The meshes' triangles, then every instance's emissive triangles in world space (instance
// by instance, in mesh order, as flatten_instances writes them with FrontStaysFront): the
// triangles an instanced scene's device shading data covers, so that light sampling reads
// world-space emitters the way it reads a flat scene's. Validates first; InputError naming
// the file when those triangles pass the limits of scene_checks.h.
Scene with_world_emitters(const InstancedScene& scene);

// The world bounds of the instances' mesh boxes (eight corners each through the transform):
// flatten_instances(scene).bounds() where every transform keeps boxes axis-aligned (scales,
// translations, axis permutations), a little larger under rotations; one pass over the mesh
// triangles and eight points per instance. `scene` must be valid.
Bounds3 world_bounds(const InstancedScene& scene);

// The world-to-object map of an instance in float, as the device gets it (the inverse
// computed in double and rounded once). Inline: the BVH module uses it without the loaders.
inline glm::mat4 world_to_object(const glm::mat4& object_to_world)
{
    return glm::mat4(glm::inverse(glm::dmat4(object_to_world)));
}

}  // namespace gc
