/*
 * raster.frag — the G-buffer of the mesh pass: shaded preview, shading normal + depth,
 * albedo, primitive id. Surface attributes come from gc_surface_at (gc_shading.h) with the
 * rasteriser's perspective-correct barycentrics, so normals and texture lookups follow the
 * ray tracer's rules. Depth is the distance along the pixel-centre camera ray to the
 * triangle's plane (what the ray tracer's depth AOV reports), not the NDC depth.
 * A glTF alphaMode MASK fragment whose alpha is below the cutoff is discarded, as the ray
 * tracer's traversal skips that hit (gc_alpha_solid, gc_alpha.h), so the surface behind it
 * is drawn instead.
 */
#version 450
#include "scene_bindings.glsl"
#include "gc_aov.h"
#include "gc_alpha.h"

layout(location = 0) in vec3 v_bary;
layout(location = 1) flat in uint v_prim;

layout(location = 0) out vec4 o_preview;
layout(location = 1) out vec4 o_normal_depth;
layout(location = 2) out vec4 o_albedo;
layout(location = 3) out int o_primid;

void main()
{
    const GcRenderParams params = params_data;
    const uint prim = v_prim;
    const GcRay ray = gc_camera_ray(params.camera, params.width, params.height, uint(gl_FragCoord.x),
                                    uint(gl_FragCoord.y), 0.5f, 0.5f);
    const vec3 o = ray.org_tmin.xyz;
    const vec3 dir = ray.dir_tmax.xyz;
    const vec3 v0 = positions[3u * prim].xyz;
    const vec3 n = cross(positions[3u * prim + 1u].xyz - v0, positions[3u * prim + 2u].xyz - v0);

    GcHit hit;
    hit.t = dot(v0 - o, n) / dot(dir, n);
    hit.u = v_bary.y;
    hit.v = v_bary.z;
    hit.prim = prim;
    const GcSurface s = gc_surface_at(attrib_data[prim], ray, hit);
    const GcMaterial m = material_data[s.material];
    if ((m.flags & GC_MATF_ALPHA_MASK) != 0u && !gc_alpha_solid(GC_ALPHA_ARGS, prim, hit.u, hit.v)) discard;
    const vec3 albedo = gc_shade_albedo(GC_SHADE_ARGS, m, s.uv);

    o_preview = vec4(gc_aov_preview(albedo, s.ns, dir, gc_shade_emission(GC_SHADE_ARGS, m, s.uv)), 1.0f);
    o_normal_depth = vec4(s.ns, hit.t);
    o_albedo = vec4(albedo, 1.0f);
    o_primid = int(prim);
}
