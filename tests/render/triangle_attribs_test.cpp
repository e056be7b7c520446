// make_triangle_attribs (host/render/scene_convert.h): large scenes are filled in parallel
// chunks into an uninitialised BigArray, so every chunk must be written, each element whole
// (fields a triangle lacks are zero), and the result must not depend on the thread count.
#include <cstring>

#include <gtest/gtest.h>

#include "host/render/scene_convert.h"
#include "host/util/host_threads.h"

namespace gc {
namespace {

using dev::GcTriangleAttribs;

// Restores "every core" when a test ends, however it ends.
struct ScopedHostThreads {
    explicit ScopedHostThreads(int threads) { set_host_thread_count(threads); }
    ~ScopedHostThreads() { set_host_thread_count(0); }
};

// `count` triangles in a row along x, each with its own normals and material; with uvs and
// per-vertex tangents on every third triangle when `textured`.
Scene strip(std::size_t count, bool textured)
{
    Scene s;
    s.materials.resize(7);
    for (std::size_t i = 0; i < count; ++i) {
        const float x = static_cast<float>(i);
        const Point3 p[3] = {Point3(x, 0, 0), Point3(x + 1, 0, 0), Point3(x, 1, 0.5f)};
        for (int j = 0; j < 3; ++j) {
            s.positions.push_back(p[j]);
            s.normals.push_back(Normal3(normalize(glm::vec3(0.1f * float(j), 0.01f * float(i % 100), 1.0f))));
            if (textured) {
                s.uvs.emplace_back(0.5f * float(j), 0.001f * float(i % 1000));
                s.tangents.push_back(i % 3 == 0 ? glm::vec4(1, 0, 0, j == 1 ? -1.0f : 1.0f) : glm::vec4(0.0f));
            }
        }
        s.material_ids.push_back(static_cast<std::uint32_t>(i % 7));
        s.has_vertex_normals.push_back(static_cast<std::uint8_t>(i % 2));
    }
    return s;
}

// 40,000 triangles: three 16k chunks, the last one partial.
constexpr std::size_t kTriangles = 40000;

TEST(TriangleAttribs, EveryChunkIsWrittenWithItsTrianglesValues)
{
    const Scene s = strip(kTriangles, false);
    const ScopedHostThreads threads(4);
    const BigArray<GcTriangleAttribs> a = make_triangle_attribs(s);
    ASSERT_EQ(a.size(), kTriangles);
    std::size_t wrong = 0;
    for (std::size_t i = 0; i < kTriangles; ++i) {
        const GcTriangleAttribs& t = a[i];
        const bool ok = t.material == s.material_ids[i] && t.n2.y == s.normals[3 * i + 2].y &&
                        t.ng.z > 0.0f && t.flags == (i % 2 ? GC_TRIF_HAS_VERTEX_NORMALS : 0u) &&
                        // No uvs: the uv and tangent fields are zero, not left as they were.
                        t.uv01 == glm::vec4(0.0f) && t.uv2_u == 0.0f && t.uv2_v == 0.0f &&
                        t.tangent == glm::vec4(0.0f);
        wrong += ok ? 0 : 1;
    }
    std::printf("triangle attributes not as the scene says: %zu of %zu\n", wrong, kTriangles);
    EXPECT_EQ(wrong, 0u);
}

TEST(TriangleAttribs, SameBytesOnOneThreadAndOnFour)
{
    for (const bool textured : {false, true}) {
        const Scene s = strip(kTriangles, textured);
        BigArray<GcTriangleAttribs> one;
        {
            const ScopedHostThreads threads(1);
            one = make_triangle_attribs(s);
        }
        const ScopedHostThreads threads(4);
        const BigArray<GcTriangleAttribs> four = make_triangle_attribs(s);
        ASSERT_EQ(one.size(), four.size());
        std::size_t differ = 0;
        for (std::size_t i = 0; i < one.size(); ++i)
            differ += std::memcmp(&one[i], &four[i], sizeof(GcTriangleAttribs)) != 0 ? 1 : 0;
        std::printf("%s: %zu of %zu triangles differ between 1 and 4 threads\n", textured ? "textured" : "plain",
                    differ, one.size());
        EXPECT_EQ(differ, 0u);
        if (textured) {
            // Authored tangents on every third triangle, packed into the normals' .w.
            EXPECT_NE(four[0].flags & GC_TRIF_HAS_TANGENTS, 0u);
            EXPECT_EQ(four[1].flags & GC_TRIF_HAS_TANGENTS, 0u);
            EXPECT_NE(four[kTriangles - 1].flags & GC_TRIF_HAS_UV, 0u);
        }
    }
}

}  // namespace
}  // namespace gc
