/*
 * raster.vert — the mesh pass's projection, built from the same GcCamera as the ray
 * tracer's primary rays (gc_camera.h): a point p is seen through the image-plane position
 * (sx, sy) with p - origin parallel to forward + sx * right + sy * up. right and up are
 * orthogonal to forward, so sx = dot(d, right) / (|right|^2 z) and sy likewise, with
 * z = dot(d, forward). Vulkan's NDC x is sx (pixel centres at +0.5 on both sides); its y
 * points down, so it is -sy (row 0 = top, as in the films).
 *
 * Depth is reversed and infinite (ndc z = near / z, cleared to 0, test GREATER): float
 * depth then has the same relative precision at every distance, so the nearest surface
 * wins where the ray tracer's closest hit does. The flat, unindexed triangle array is one
 * draw: triangle i is vertices 3i .. 3i+2.
 */
#version 450
#include "scene_bindings.glsl"

layout(push_constant) uniform Push { float near; } push;

layout(location = 0) out vec3 v_bary;
layout(location = 1) flat out uint v_prim;

void main()
{
    const GcCamera cam = params_data.camera;
    const vec3 d = positions[gl_VertexIndex].xyz - cam.origin.xyz;
    const vec3 r = cam.right.xyz;
    const vec3 u = cam.up.xyz;
    const float z = dot(d, cam.forward.xyz);
    const float x = dot(d, r) / dot(r, r);
    const float y = dot(d, u) / dot(u, u);
    gl_Position = vec4(x, -y, push.near, z);
    const int corner = gl_VertexIndex - 3 * (gl_VertexIndex / 3);
    v_bary = vec3(corner == 0 ? 1.0f : 0.0f, corner == 1 ? 1.0f : 0.0f, corner == 2 ? 1.0f : 0.0f);
    v_prim = uint(gl_VertexIndex / 3);
}
