// Khronos' glTF sample models of the KHR material extensions, rendered on the device and
// checked against what each model's README says a correct renderer shows (the README beside
// each model in tests/data/scenes quotes it):
//   SpecularTest               KHR_materials_specular: factor, colour and their textures
//   TransmissionRoughnessTest  KHR_materials_transmission + _ior + _volume: blur grows with IOR
//   AttenuationTest            KHR_materials_volume: one shade of blue down each column
//   SheenCloth                 KHR_materials_sheen (with KHR_mesh_quantization and
//                              KHR_texture_transform)
// A pixel is told to belong to an object by its first hit (the primid AOV): the triangle's
// material and, where one material covers several objects, the triangle's position.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "host/bvh/bvh.h"
#include "host/render/aov_layers.h"
#include "host/render/renderer.h"
#include "host/scene/camera_framing.h"
#include "host/scene/load.h"
#include "host/scene/triangle_sink.h"
#include "tests/cl/cl_test_util.h"

namespace gc {
namespace {

constexpr std::uint32_t k_miss = 0xffffffffu;

Scene load_sample(const std::string& name)
{
    return load_scene(std::filesystem::path(GC_TEST_SOURCE_DIR) / "tests/data/scenes" / name / (name + ".glb"));
}

// One image: the mean radiance and the first hit's scene triangle of every pixel.
struct Shot {
    std::vector<glm::vec3> radiance;
    std::vector<std::uint32_t> triangle;
};

Shot shoot(const cl::Context& context, const Scene& scene, const Camera& camera, int width, int height,
           std::uint32_t spp, const glm::vec3& env)
{
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.env_radiance = env;
    Renderer renderer(context, scene, build_bvh(scene), camera, settings);
    renderer.render(0, spp);
    const Film image = renderer.film();
    const Film hit = render_aov_like(renderer, AovKind::PrimitiveId, 1);
    Shot shot;
    for (std::size_t i = 0; i < image.pixel_count(); ++i) {
        const float* p = image.data().data() + 4 * i;
        shot.radiance.emplace_back(p[0], p[1], p[2]);
        const float id = hit.data()[4 * i];
        shot.triangle.push_back(id < 0.0f ? k_miss : static_cast<std::uint32_t>(id));
    }
    return shot;
}

glm::vec3 centroid(const Scene& s, std::uint32_t tri)
{
    return (s.vertex(tri, 0).glm() + s.vertex(tri, 1).glm() + s.vertex(tri, 2).glm()) / 3.0f;
}

glm::vec3 triangle_normal(const Scene& s, std::uint32_t tri)
{
    return face_normal(s.vertex(tri, 0), s.vertex(tri, 1), s.vertex(tri, 2)).glm();
}

// The cosine between a triangle's normal and the direction from its centroid to the camera.
float facing_camera(const Scene& s, std::uint32_t tri, const Camera& camera)
{
    return glm::dot(triangle_normal(s, tri), glm::normalize(camera.look_from.glm() - centroid(s, tri)));
}

const std::string& material_name(const Scene& s, std::uint32_t tri) { return s.materials[s.material_ids[tri]].name; }

// The index of the value in `centres` nearest to x.
int nearest(const std::vector<float>& centres, float x)
{
    int best = 0;
    for (int i = 1; i < static_cast<int>(centres.size()); ++i)
        if (std::abs(centres[i] - x) < std::abs(centres[best] - x)) best = i;
    return best;
}

// Makes the backdrop of Ed Mackey's test models (material "FlatBackdrop") reflect nothing and
// emit: its own pattern (the base colour texture) where `patterned`, else a plain white.
// Returns how many materials it changed.
int make_backdrop_emit(Scene& s, bool patterned)
{
    int changed = 0;
    for (Material& m : s.materials)
        if (m.name == "FlatBackdrop") {
            m.emission = glm::vec3(1.0f);
            m.emission_texture = patterned ? m.albedo_texture : -1;
            m.albedo = glm::vec3(0.0f);
            m.albedo_texture = -1;
            ++changed;
        }
    return changed;
}

// The mean radiance of a set of pixels.
struct Region {
    glm::dvec3 sum{0.0};
    std::size_t pixels = 0;
    void add(const glm::vec3& v) { sum += glm::dvec3(v), ++pixels; }
    glm::vec3 mean() const { return pixels ? glm::vec3(sum / double(pixels)) : glm::vec3(0.0f); }
};

// ---- SpecularTest ----------------------------------------------------------------------------

// Seven rows of five smooth black spheres (README): 1 specularFactor 0..1, 2 the same through
// specularTexture, 3 specularColorFactor grey 0..1, 4 the same through specularColorTexture,
// 5 and 6 a yellow ramp, 7 specularColorFactor 0..25. Rows 2, 4 and 6 are one material each;
// their spheres stand in the columns of row 1's.
class SpecularTestModel : public cl::test::DeviceTest {
protected:
    void SetUp() override
    {
        cl::test::DeviceTest::SetUp();
        if (IsSkipped()) return;
        scene = load_sample("SpecularTest");
        camera = frame_camera(scene);
        // A white sky: at a sphere's centre the mirror direction points back past the camera,
        // so the pixel shows the Fresnel factor at normal incidence, F0, times 1.
        const Shot shot = shoot(*context, scene, camera, 384, 288, 32, glm::vec3(1.0f));
        std::vector<float> columns;
        for (int k = 1; k <= 5; ++k) {
            Region x;
            for (std::uint32_t t = 0; t < scene.triangle_count(); ++t)
                if (material_name(scene, t) == "M1." + std::to_string(k) + "_specFac") x.add(centroid(scene, t));
            ASSERT_GT(x.pixels, 0u) << "row 1 sphere " << k;
            columns.push_back(x.mean().x);
        }
        for (std::size_t i = 0; i < shot.triangle.size(); ++i) {
            const std::uint32_t t = shot.triangle[i];
            if (t == k_miss) continue;
            const std::string& m = material_name(scene, t);
            if (m.size() < 2 || m[0] != 'M' || m[1] < '1' || m[1] > '7') continue;  // the labels
            const glm::vec3 c = centroid(scene, t);
            const std::string key = m.substr(0, 2) + "#" + std::to_string(nearest(columns, c.x) + 1);
            const float facing = facing_camera(scene, t, camera);
            if (facing > 0.95f) centre[key].add(shot.radiance[i]);
            if (facing < 0.5f) rim[key].add(shot.radiance[i]);
            // Away from the outline, where a pixel's samples see the sky beside the sphere.
            if (key == "M1#1" && facing > 0.5f)
                row1_first_max = std::max(row1_first_max, glm::length(shot.radiance[i]));
        }
    }

    // Rows are M1..M7, columns 1..5: "M3#2" is row 3's second sphere.
    static std::string sphere(int row, int column) { return "M" + std::to_string(row) + "#" + std::to_string(column); }

    Scene scene;
    Camera camera;
    std::map<std::string, Region> centre, rim;
    float row1_first_max = 0.0f;
};

TEST_F(SpecularTestModel, CentresShowTheSpecularF0)
{
    // Row 1: F0 = 0.04 specularFactor (IOR 1.5); row 3: 0.04 times the grey; row 7: min(0.04 c, 1).
    const float factors[5] = {0.0f, 0.051269f, 0.212231f, 0.520996f, 1.0f};
    const float hdr[5] = {0.0f, 1.184f, 5.441f, 13.276f, 25.0f};
    for (int k = 1; k <= 5; ++k) {
        for (int row : {1, 3, 7}) {
            const Region& r = centre[sphere(row, k)];
            ASSERT_GT(r.pixels, 20u) << sphere(row, k);
            const float expected = std::min(0.04f * (row == 7 ? hdr[k - 1] : factors[k - 1]), 1.0f);
            const float got = r.mean().y;
            std::printf("row %d sphere %d: centre %.5f, F0 %.5f\n", row, k, got, expected);
            EXPECT_NEAR(got, expected, 0.05f * expected + 2e-4f) << sphere(row, k);
        }
    }
    std::printf("row 1's first sphere (specularFactor 0): brightest pixel inside its outline %.3g\n", row1_first_max);
    EXPECT_EQ(row1_first_max, 0.0f) << "the leftmost sphere of row 1 should be perfectly black";
}

TEST_F(SpecularTestModel, TextureRowsMatchTheFactorRows)
{
    for (int row : {2, 4, 6})
        for (int k = 1; k <= 5; ++k) {
            const glm::vec3 textured = centre[sphere(row, k)].mean();
            const glm::vec3 factor = centre[sphere(row - 1, k)].mean();
            ASSERT_GT(centre[sphere(row, k)].pixels, 20u) << sphere(row, k);
            std::printf("sphere %d: row %d centre (%.5f %.5f %.5f), row %d (%.5f %.5f %.5f)\n", k, row, textured.x,
                        textured.y, textured.z, row - 1, factor.x, factor.y, factor.z);
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(textured[c], factor[c], 0.05f * factor[c] + 3e-4f) << sphere(row, k) << " channel " << c;
        }
}

TEST_F(SpecularTestModel, ColourChangesTheCentresNotTheEdges)
{
    // Row 3's first sphere (specularColorFactor 0) is black in the middle, but its edges keep
    // the F90 of the last one; row 5's yellow leaves blue out of the centres only.
    const Region &grey0_centre = centre[sphere(3, 1)], &grey1_centre = centre[sphere(3, 5)];
    const Region &grey0_rim = rim[sphere(3, 1)], &grey1_rim = rim[sphere(3, 5)];
    const glm::vec3 yellow_centre = centre[sphere(5, 5)].mean(), yellow_rim = rim[sphere(5, 5)].mean();
    ASSERT_GT(grey0_rim.pixels, 20u);
    ASSERT_GT(rim[sphere(5, 5)].pixels, 20u);
    std::printf("row 3: colour 0 centre %.5f rim %.4f; colour 1 centre %.5f rim %.4f\n", grey0_centre.mean().y,
                grey0_rim.mean().y, grey1_centre.mean().y, grey1_rim.mean().y);
    std::printf("row 5, yellow 1: centre (%.4f %.4f %.4f), rim (%.4f %.4f %.4f)\n", yellow_centre.x,
                yellow_centre.y, yellow_centre.z, yellow_rim.x, yellow_rim.y, yellow_rim.z);
    EXPECT_LT(grey0_centre.mean().y, 0.02f * grey1_centre.mean().y);
    EXPECT_GT(grey0_rim.mean().y, 0.6f * grey1_rim.mean().y);
    EXPECT_LT(yellow_centre.z, 0.02f * yellow_centre.x);
    EXPECT_GT(yellow_rim.z, 0.6f * yellow_rim.x);
}

// ---- TransmissionRoughnessTest ----------------------------------------------------------------

class SampleModelTest : public cl::test::DeviceTest {};

// Rows of transmissive tiles, IOR 1.0 to 2.42, in nine columns of roughness 0 to 1 (a
// texture), before a patterned backdrop. README: at IOR 1.0 "light vectors do not change
// regardless of how strong the microfacet angles become", so the row is sharp at any
// roughness; above it the transmitted image blurs, the more the higher the IOR, which the
// second column shows most clearly. Each pixel is compared with the same render with the
// tiles' roughness at 0, the backdrop's pattern made to emit under a black sky (every pixel is
// then the pattern seen through a tile). Per tile: the brightness ratio, and the detail kept,
// the regression slope of the rough image's horizontal pixel differences on the smooth
// image's (1: as sharp; 0: no detail left; noise, uncorrelated with the pattern, does not bias it).
TEST_F(SampleModelTest, TransmissionRoughnessTestBlursMoreAtHigherIor)
{
    Scene rough = load_sample("TransmissionRoughnessTest");
    ASSERT_EQ(make_backdrop_emit(rough, true), 1);
    const std::vector<std::string> rows = {"Mat_IOR_1.0", "Mat_IOR_1.33", "Mat_IOR_1.50", "Mat_IOR_1.76",
                                           "Mat_IOR_2.42"};
    Scene smooth = rough;
    for (Material& m : smooth.materials)
        if (std::find(rows.begin(), rows.end(), m.name) != rows.end()) {
            ASSERT_GE(m.metallic_roughness_texture, 0) << m.name << ": the roughness ramp is a texture";
            m.metallic_roughness_texture = -1;  // its B (metallic) is 0 throughout
            m.roughness = 0.0f;
            m.metallic = 0.0f;
        }
    Camera camera;  // the tiles, face-on
    camera.look_from = Point3(0.15f, -0.05f, 2.0f);
    camera.look_at = Point3(0.15f, -0.05f, 0.0f);
    camera.vfov_degrees = 22.0f;
    const int width = 200, height = 160, columns = 9;
    const Shot a = shoot(*context, rough, camera, width, height, 32, glm::vec3(0.0f));
    const Shot b = shoot(*context, smooth, camera, width, height, 32, glm::vec3(0.0f));
    auto sum = [](const glm::vec3& v) { return double(v.x) + v.y + v.z; };
    std::vector<double> second_column_detail;
    for (const std::string& row : rows) {
        float lo = 1e30f, hi = -1e30f;
        for (std::uint32_t t = 0; t < rough.triangle_count(); ++t)
            if (material_name(rough, t) == row) {
                lo = std::min(lo, centroid(rough, t).x);
                hi = std::max(hi, centroid(rough, t).x);
            }
        auto column_of = [&](std::uint32_t t) {
            return std::min(columns - 1, static_cast<int>(columns * (centroid(rough, t).x - lo) / (hi - lo)));
        };
        std::vector<double> level_a(columns), level_b(columns), cross(columns), square(columns);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x + 1 < width; ++x) {
                const std::size_t i = std::size_t(y) * width + x;
                const std::uint32_t t = a.triangle[i], u = a.triangle[i + 1];
                if (t == k_miss || u == k_miss || material_name(rough, t) != row || material_name(rough, u) != row ||
                    column_of(t) != column_of(u))
                    continue;
                const int c = column_of(t);
                level_a[c] += sum(a.radiance[i]);
                level_b[c] += sum(b.radiance[i]);
                const glm::vec3 da = a.radiance[i + 1] - a.radiance[i], db = b.radiance[i + 1] - b.radiance[i];
                cross[c] += glm::dot(da, db);
                square[c] += glm::dot(db, db);
            }
        std::printf("%-13s brightness / detail kept, roughness 0 to 1:", row.c_str());
        for (int c = 0; c < columns; ++c) {
            ASSERT_GT(square[c], 0.0) << row << " column " << c + 1;
            const double brightness = level_a[c] / level_b[c], detail = cross[c] / square[c] / brightness;
            std::printf(" %.2f/%.2f", brightness, detail);
            if (row == rows[0]) {
                EXPECT_GT(brightness, 0.98) << "IOR 1.0 loses light at roughness column " << c + 1;
                EXPECT_GT(detail, 0.95) << "IOR 1.0 blurs at roughness column " << c + 1;
            }
            if (c == 1) second_column_detail.push_back(detail);
        }
        std::printf("\n");
    }
    for (std::size_t r = 0; r + 1 < rows.size(); ++r)
        EXPECT_GT(second_column_detail[r], second_column_detail[r + 1] + 0.03)
            << rows[r + 1] << " should blur the second column more than " << rows[r];
}

// ---- AttenuationTest -------------------------------------------------------------------------

// Five rows of blue glass and five columns of thickness t = 0.25 .. 2 (README): row 1 a thin
// sheet whose base colour is the answer key, rows 2-5 cubes of edge t (by size, by thickness
// texture, by node scale) or unit cubes whose attenuation distance is 1 / t. Seen face-on,
// every one of a column transmits attenuationColor^t = (0.1, 0.5, 0.9)^t, so "each vertical
// column shows one shade of blue". Measured as the mean of the pixels inside each front face
// over their mean in the same render with clear glass (attenuationColor 1, sheets white),
// before a white emitting backdrop under a black sky: the Fresnel factors cancel and the
// ratio is the transmittance alone.
TEST_F(SampleModelTest, AttenuationTestColumnsShowTheSpecifiedTransmittance)
{
    Scene tinted = load_sample("AttenuationTest");
    ASSERT_EQ(make_backdrop_emit(tinted, false), 1);
    Scene clear = tinted;
    for (Material& m : clear.materials) {
        if (m.layers.volume_on) m.layers.attenuation_color = glm::vec3(1.0f);
        if (m.name.rfind("R1_Sample", 0) == 0) m.albedo = glm::vec3(1.0f);
    }
    // Far away with a narrow view: nearly parallel rays, face-on to every cube.
    Camera camera;
    camera.look_from = Point3(1.25f, 0.25f, 1000.0f);
    camera.look_at = Point3(1.25f, 0.25f, 0.0f);
    camera.vfov_degrees = 2.0f * std::atan(7.5f / 1000.0f) * 180.0f / 3.14159265f;
    const int size = 256;
    const Shot a = shoot(*context, tinted, camera, size, size, 16, glm::vec3(0.0f));
    const Shot b = shoot(*context, clear, camera, size, size, 16, glm::vec3(0.0f));

    const std::vector<float> row_y = {6.0f, 3.0f, 0.0f, -3.0f, -6.0f};
    const std::vector<float> column_x = {-3.5f, -2.0f, 0.0f, 2.5f, 6.0f};
    const float thickness[5] = {0.25f, 0.5f, 1.0f, 1.5f, 2.0f};
    // The row * 5 + column of the glass a pixel sees face-on, -1 for anything else.
    auto glass_at = [&](int x, int y) {
        const std::uint32_t t = a.triangle[std::size_t(y) * size + x];
        if (t == k_miss || tinted.materials[tinted.material_ids[t]].transmission <= 0.0f ||
            std::abs(triangle_normal(tinted, t).z) < 0.99f)
            return -1;
        const glm::vec3 c = centroid(tinted, t);
        return nearest(row_y, c.y) * 5 + nearest(column_x, c.x);
    };
    std::map<int, Region> seen_tinted, seen_clear;
    for (int y = 1; y + 1 < size; ++y)
        for (int x = 1; x + 1 < size; ++x) {
            const int g = glass_at(x, y);
            // Inside the face: all eight neighbours see it too (no pixel straddles an edge).
            bool inside = g >= 0;
            for (int dy = -1; dy <= 1 && inside; ++dy)
                for (int dx = -1; dx <= 1 && inside; ++dx) inside = glass_at(x + dx, y + dy) == g;
            if (!inside) continue;
            seen_tinted[g].add(a.radiance[std::size_t(y) * size + x]);
            seen_clear[g].add(b.radiance[std::size_t(y) * size + x]);
        }
    for (int column = 0; column < 5; ++column)
        for (int row = 0; row < 5; ++row) {
            const int g = row * 5 + column;
            ASSERT_GE(seen_tinted[g].pixels, 4u) << "row " << row + 1 << ", thickness " << thickness[column];
            const glm::vec3 ratio = seen_tinted[g].mean() / seen_clear[g].mean();
            const glm::vec3 expected = glm::pow(glm::vec3(0.1f, 0.5f, 0.9f), glm::vec3(thickness[column]));
            std::printf("thickness %.2f, row %d (%zu pixels): transmittance (%.4f %.4f %.4f), specified "
                        "(%.4f %.4f %.4f)\n",
                        thickness[column], row + 1, seen_tinted[g].pixels, ratio.x, ratio.y, ratio.z, expected.x,
                        expected.y, expected.z);
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(ratio[c], expected[c], 0.04f * expected[c] + 0.003f)
                    << "row " << row + 1 << ", thickness " << thickness[column] << ", channel " << c;
        }
}

// ---- SheenCloth ------------------------------------------------------------------------------

// A draped technical fabric (README): a tiled blue base colour, a sheen colour and roughness
// texture, vertices quantized (KHR_mesh_quantization, required) and textures tiled through
// KHR_texture_transform. Charlie sheen is a grazing-angle lobe: with it the cloth's grazing
// folds brighten against the same cloth without it, more than where the cloth faces the view,
// where the sheen takes its share from the layers beneath (the spec's albedo scaling). Nothing
// is non-finite, and the cloth stays blue.
TEST_F(SampleModelTest, SheenClothShowsItsSheen)
{
    const Scene with = load_sample("SheenCloth");
    ASSERT_EQ(with.materials.size(), 1u);
    const PbrLayers& layers = with.materials[0].layers;
    ASSERT_TRUE(layers.sheen_on);
    EXPECT_GE(layers.sheen_color_texture.texture, 0);
    EXPECT_GE(layers.sheen_roughness_texture.texture, 0);
    Scene without = with;
    without.materials[0].layers.sheen_on = false;
    const Camera camera = frame_camera(with);
    const Shot a = shoot(*context, with, camera, 128, 128, 16, glm::vec3(1.0f));
    const Shot b = shoot(*context, without, camera, 128, 128, 16, glm::vec3(1.0f));
    Region grazing_with, grazing_without, facing_with, facing_without, cloth;
    std::size_t non_finite = 0;
    for (std::size_t i = 0; i < a.triangle.size(); ++i) {
        const std::uint32_t t = a.triangle[i];
        if (t == k_miss) continue;
        non_finite += std::isfinite(a.radiance[i].x + a.radiance[i].y + a.radiance[i].z) ? 0 : 1;
        cloth.add(a.radiance[i]);
        const float facing = std::abs(facing_camera(with, t, camera));
        if (facing < 0.3f) grazing_with.add(a.radiance[i]), grazing_without.add(b.radiance[i]);
        if (facing > 0.8f) facing_with.add(a.radiance[i]), facing_without.add(b.radiance[i]);
    }
    auto total = [](const Region& r) { return r.mean().x + r.mean().y + r.mean().z; };
    std::printf("cloth: %zu pixels, %zu non-finite; grazing (%zu pixels) %.4f with sheen, %.4f without; facing "
                "(%zu pixels) %.4f with, %.4f without\n",
                cloth.pixels, non_finite, grazing_with.pixels, total(grazing_with), total(grazing_without),
                facing_with.pixels, total(facing_with), total(facing_without));
    ASSERT_GT(grazing_with.pixels, 200u);
    ASSERT_GT(facing_with.pixels, 200u);
    EXPECT_EQ(non_finite, 0u);
    const float grazing_gain = total(grazing_with) / total(grazing_without);
    const float facing_gain = total(facing_with) / total(facing_without);
    EXPECT_GT(grazing_gain, 1.01f);
    EXPECT_GT(grazing_gain, facing_gain + 0.02f);
    EXPECT_GT(cloth.mean().z, 1.3f * cloth.mean().x);
}

}  // namespace
}  // namespace gc
