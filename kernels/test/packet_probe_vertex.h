/*
 * packet_probe_vertex.h — the body of packet_probe.cl's kernels, included once per lane count
 * (GC_PROBE_LANES = 1, 8 or 16): the same source text becomes a scalar kernel and two kernels
 * that hold 8 or 16 vertices in OpenCL vector lanes. Relational operators give 1 in a scalar
 * and -1 in a vector lane, and select() reads "non-zero" and "top bit set" respectively, so
 * every line below means the same lane for lane.
 */
#if GC_PROBE_LANES == 1
#define PROBE_FLOAT float
#define PROBE_INT int
#define PROBE_UINT uint
#define PROBE_LANE_IDS 0u
#define PROBE_TO_FLOAT(bits) convert_float(as_int(bits))
#define PROBE_LOAD(p, g) ((p)[g])
#define PROBE_STORE(v, p, g) ((p)[g] = (v))
#define PROBE_KERNEL packet_probe_x1
#elif GC_PROBE_LANES == 8
#define PROBE_FLOAT float8
#define PROBE_INT int8
#define PROBE_UINT uint8
#define PROBE_LANE_IDS (uint8)(0u, 1u, 2u, 3u, 4u, 5u, 6u, 7u)
#define PROBE_TO_FLOAT(bits) convert_float8(as_int8(bits))
#define PROBE_LOAD(p, g) vload8((g), (p))
#define PROBE_STORE(v, p, g) vstore8((v), (g), (p))
#define PROBE_KERNEL packet_probe_x8
#elif GC_PROBE_LANES == 16
#define PROBE_FLOAT float16
#define PROBE_INT int16
#define PROBE_UINT uint16
#define PROBE_LANE_IDS (uint16)(0u, 1u, 2u, 3u, 4u, 5u, 6u, 7u, 8u, 9u, 10u, 11u, 12u, 13u, 14u, 15u)
#define PROBE_TO_FLOAT(bits) convert_float16(as_int16(bits))
#define PROBE_LOAD(p, g) vload16((g), (p))
#define PROBE_STORE(v, p, g) vstore16((v), (g), (p))
#define PROBE_KERNEL packet_probe_x16
#else
#error "GC_PROBE_LANES must be 1, 8 or 16"
#endif

/* Vertices [g * lanes, (g + 1) * lanes) of `count` (a multiple of 16). */
__kernel void PROBE_KERNEL(__global const float* px, __global const float* py, __global const float* pz,
                           __global const float* nx, __global const float* ny, __global const float* nz,
                           __global const float* ax, __global const float* ay, __global const float* az,
                           __global float* light_r, __global float* light_g, __global float* light_b,
                           __global float* dir_x, __global float* dir_y, __global float* dir_z, const uint seed,
                           const uint count)
{
    const uint g = get_global_id(0);
    if (g >= count / GC_PROBE_LANES) return;
    const PROBE_UINT vertex = (PROBE_UINT)(g * GC_PROBE_LANES) + PROBE_LANE_IDS;
    const PROBE_FLOAT p0 = PROBE_LOAD(px, g), p1 = PROBE_LOAD(py, g), p2 = PROBE_LOAD(pz, g);
    const PROBE_FLOAT n0 = PROBE_LOAD(nx, g), n1 = PROBE_LOAD(ny, g), n2 = PROBE_LOAD(nz, g);

    /* Four hashes of the vertex index, mapped to [0, 1) by their top 24 bits (as gc_rng.h). */
    const PROBE_UINT h0 = vertex * 2654435761u, h1 = vertex * 40503u + seed;
    const PROBE_UINT h2 = vertex * 747796405u, h3 = vertex * 2891336453u + seed;
    const float to_unit = 1.0f / 16777216.0f;
    const PROBE_FLOAT u0 = PROBE_TO_FLOAT(h0 >> 8u) * to_unit, u1 = PROBE_TO_FLOAT(h1 >> 8u) * to_unit;
    const PROBE_FLOAT u2 = PROBE_TO_FLOAT(h2 >> 8u) * to_unit, u3 = PROBE_TO_FLOAT(h3 >> 8u) * to_unit;

    /* Next-event estimation: a point on a 0.5 x 0.5 light facing down at y = 1.98, the
     * cosines at both ends, and the power-heuristic weight against the BSDF's pdf. */
    const PROBE_FLOAT lx = -0.25f + 0.5f * u0 - p0, ly = 1.98f - p1, lz = -0.25f + 0.5f * u1 - p2;
    const PROBE_FLOAT dist = sqrt(lx * lx + ly * ly + lz * lz);
    const PROBE_FLOAT cos_light = ly / dist;
    const PROBE_FLOAT cos_surface = (n0 * lx + n1 * ly + n2 * lz) / dist;
    const PROBE_FLOAT pdf_light = dist * dist / (cos_light * 0.25f);
    const PROBE_FLOAT pdf_bsdf = cos_surface * M_1_PI_F;
    const PROBE_FLOAT mis = pdf_light * pdf_light / (pdf_light * pdf_light + pdf_bsdf * pdf_bsdf);
    const PROBE_FLOAT lit = M_1_PI_F * (cos_surface * mis / pdf_light);
    const PROBE_INT visible = cos_light > 0.0f && cos_surface > 0.0f;
    const PROBE_FLOAT k = select((PROBE_FLOAT)(0.0f), lit, visible);
    PROBE_STORE(PROBE_LOAD(ax, g) * k * 17.0f, light_r, g);
    PROBE_STORE(PROBE_LOAD(ay, g) * k * 12.0f, light_g, g);
    PROBE_STORE(PROBE_LOAD(az, g) * k * 4.0f, light_b, g);

    /* A cosine-weighted direction: Shirley-Chiu's concentric map with polynomial sine and
     * cosine (as gc_trig.h), lifted to the hemisphere, then Duff et al.'s frame around n. */
    const PROBE_FLOAT a = 2.0f * u2 - 1.0f, b = 2.0f * u3 - 1.0f;
    const PROBE_INT a_wider = a * a > b * b;
    const PROBE_INT at_centre = a == 0.0f && b == 0.0f;
    const PROBE_FLOAT r = select(b, a, a_wider);
    const PROBE_FLOAT x = select((0.25f * M_PI_F) * (a / b), (0.25f * M_PI_F) * (b / a), a_wider);
    const PROBE_FLOAT x2 = x * x;
    const PROBE_FLOAT sine = x + x * x2 * (-0.166666552f + x2 * (0.00833216123f + x2 * -0.000195153087f));
    const PROBE_FLOAT cosine = 1.0f - 0.5f * x2 + x2 * x2 * (0.0416666456f + x2 * (-0.00138873165f + x2 * 2.44331768e-05f));
    const PROBE_FLOAT du = select(select(r * sine, r * cosine, a_wider), (PROBE_FLOAT)(0.0f), at_centre);
    const PROBE_FLOAT dv = select(select(r * cosine, r * sine, a_wider), (PROBE_FLOAT)(0.0f), at_centre);
    const PROBE_FLOAT rest = 1.0f - du * du - dv * dv;
    const PROBE_FLOAT dw = sqrt(select((PROBE_FLOAT)(0.0f), rest, rest > 0.0f));
    const PROBE_FLOAT sign = select((PROBE_FLOAT)(-1.0f), (PROBE_FLOAT)(1.0f), n2 >= 0.0f);
    const PROBE_FLOAT f = -1.0f / (sign + n2);
    const PROBE_FLOAT c = n0 * n1 * f;
    PROBE_STORE(du * (1.0f + sign * n0 * n0 * f) + dv * c + dw * n0, dir_x, g);
    PROBE_STORE(du * (sign * c) + dv * (sign + n1 * n1 * f) + dw * n1, dir_y, g);
    PROBE_STORE(du * (-sign * n0) + dv * (-n1) + dw * n2, dir_z, g);
}

#undef PROBE_FLOAT
#undef PROBE_INT
#undef PROBE_UINT
#undef PROBE_LANE_IDS
#undef PROBE_TO_FLOAT
#undef PROBE_LOAD
#undef PROBE_STORE
#undef PROBE_KERNEL
