// The command line: every option parses, every bad value is a UsageError naming the option.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "host/app/options.h"
#include "host/util/error.h"

namespace gc {
namespace {

Options parse(std::vector<std::string> args) { return parse_options(args); }

std::string usage_error(std::vector<std::string> args)
{
    try {
        parse_options(args);
    } catch (const UsageError& e) {
        EXPECT_EQ(e.code(), ExitCode::Usage);
        return e.what();
    }
    ADD_FAILURE() << "no UsageError";
    return {};
}

TEST(Options, Defaults)
{
    const Options o = parse({"scene.obj"});
    EXPECT_EQ(o.scene_path, "scene.obj");
    EXPECT_EQ(o.device, "any");
    EXPECT_EQ(o.render.integrator, IntegratorKind::Path);
    EXPECT_EQ(o.render.width, 512);
    EXPECT_EQ(o.render.height, 512);
    EXPECT_EQ(o.render.spp, 64u);
    EXPECT_EQ(o.render.max_depth, 8u);
    EXPECT_EQ(o.threads, 0);
    EXPECT_EQ(o.render.samples_per_pass, 0u);  // planned by the renderer
    EXPECT_EQ(o.render.sampler, SamplerKind::Sobol);
    EXPECT_TRUE(o.output_path.empty());
}

TEST(Options, EveryOptionParses)
{
    const Options o = parse({"--device", "gpu", "-o", "x.exr", "--integrator=whitted", "--spp", "9", "--seed", "3",
                             "--max-depth", "4", "--rr-depth", "2", "--time-limit", "1.5", "--res", "64x32",
                             "--env", "1,0.5,0.25", "--look-from", "0,1,4", "--look-at", "0,1,0", "--up", "0,1,0",
                             "--fov", "45", "--gltf-scene", "2", "--quiet", "--threads", "3", "--wavefront-size", "4096",
                             "--samples-per-pass", "5", "--sampler", "independent", "scene.glb"});
    EXPECT_EQ(o.device, "gpu");
    EXPECT_EQ(o.output_path, "x.exr");
    EXPECT_EQ(o.render.integrator, IntegratorKind::Whitted);
    EXPECT_EQ(o.render.spp, 9u);
    EXPECT_TRUE(o.spp_given);
    EXPECT_EQ(o.render.seed, 3u);
    EXPECT_EQ(o.render.max_depth, 4u);
    EXPECT_EQ(o.render.rr_depth, 2u);
    EXPECT_EQ(o.render.wavefront_size, 4096u);
    EXPECT_EQ(o.render.samples_per_pass, 5u);
    EXPECT_EQ(o.render.sampler, SamplerKind::Independent);
    EXPECT_DOUBLE_EQ(o.render.time_limit_seconds, 1.5);
    EXPECT_EQ(o.render.width, 64);
    EXPECT_EQ(o.render.height, 32);
    EXPECT_EQ(o.render.env_radiance, glm::vec3(1.0f, 0.5f, 0.25f));
    ASSERT_TRUE(o.look_from && o.look_at && o.up && o.fov_degrees);
    EXPECT_EQ(*o.look_from, Point3(0, 1, 4));
    EXPECT_EQ(*o.fov_degrees, 45.0f);
    EXPECT_EQ(o.gltf_scene, 2);
    EXPECT_TRUE(o.quiet);
    EXPECT_EQ(o.threads, 3);
    EXPECT_EQ(o.scene_path, "scene.glb");
}

TEST(Options, AovImpliesTheAovIntegrator)
{
    const Options o = parse({"--aov", "primid", "s.obj"});
    EXPECT_EQ(o.render.integrator, IntegratorKind::Aov);
    EXPECT_EQ(o.render.aov, AovKind::PrimitiveId);
}

TEST(Options, ListDevicesAndHelpNeedNoScene)
{
    EXPECT_TRUE(parse({"--list-devices"}).list_devices);
    EXPECT_TRUE(parse({"--help"}).help);
    EXPECT_TRUE(parse({"--version"}).version);
    EXPECT_NE(usage_text().find("Exit status"), std::string::npos);
}

TEST(Options, BadInputIsAUsageErrorNamingTheOption)
{
    EXPECT_NE(usage_error({"--frobnicate", "s.obj"}).find("unknown option '--frobnicate'"), std::string::npos);
    EXPECT_NE(usage_error({}).find("no scene"), std::string::npos);
    EXPECT_NE(usage_error({"a.obj", "b.obj"}).find("more than one scene"), std::string::npos);
    EXPECT_NE(usage_error({"--spp", "0", "s.obj"}).find("--spp"), std::string::npos);
    EXPECT_NE(usage_error({"--spp", "ten", "s.obj"}).find("'ten'"), std::string::npos);
    EXPECT_NE(usage_error({"--spp", "99999999999", "s.obj"}).find("--spp"), std::string::npos);
    EXPECT_NE(usage_error({"--res", "0x0", "s.obj"}).find("--res"), std::string::npos);
    EXPECT_NE(usage_error({"--res", "100000x1", "s.obj"}).find("--res"), std::string::npos);
    EXPECT_NE(usage_error({"--res", "512", "s.obj"}).find("WIDTHxHEIGHT"), std::string::npos);
    EXPECT_NE(usage_error({"--env", "1,2", "s.obj"}).find("--env"), std::string::npos);
    EXPECT_NE(usage_error({"--env", "-1,0,0", "s.obj"}).find("non-negative"), std::string::npos);
    EXPECT_NE(usage_error({"--fov", "180", "s.obj"}).find("--fov"), std::string::npos);
    EXPECT_NE(usage_error({"--fov", "nan", "s.obj"}).find("--fov"), std::string::npos);
    EXPECT_NE(usage_error({"--integrator", "bdpt", "s.obj"}).find("path, whitted, aov"), std::string::npos);
    EXPECT_NE(usage_error({"--sampler", "halton", "s.obj"}).find("independent, sobol"), std::string::npos);
    EXPECT_NE(usage_error({"--time-limit", "-3", "s.obj"}).find("--time-limit"), std::string::npos);
    EXPECT_NE(usage_error({"--up", "0,0,0", "s.obj"}).find("--up"), std::string::npos);
    EXPECT_NE(usage_error({"--look-from", "1,1,1", "--look-at", "1,1,1", "s.obj"}).find("differ"), std::string::npos);
    EXPECT_NE(usage_error({"s.obj", "--spp"}).find("needs a value"), std::string::npos);
    EXPECT_NE(usage_error({"--threads", "0", "s.obj"}).find("--threads expects an integer in [1, 4096]"), std::string::npos);
    EXPECT_NE(usage_error({"--threads", "all", "s.obj"}).find("--threads"), std::string::npos);
}

}  // namespace
}  // namespace gc

namespace gc {
namespace {

TEST(Options, DisplayAndDenoise)
{
    const Options defaults = parse({"scene.obj"});
    EXPECT_FALSE(defaults.tonemap);
    EXPECT_FALSE(defaults.exposure_ev);
    EXPECT_FALSE(defaults.denoise);
    const Options o = parse({"--tonemap", "agx", "--exposure=-1.5", "--denoise", "scene.obj"});
    EXPECT_EQ(o.tonemap, Tonemap::Agx);
    EXPECT_EQ(o.exposure_ev, -1.5f);
    EXPECT_TRUE(o.denoise);
    for (const char* name : {"none", "clamp", "pbr-neutral", "agx", "aces"})
        EXPECT_EQ(tonemap_name(*parse({"--tonemap", name, "s.obj"}).tonemap), std::string(name));
    EXPECT_NE(usage_error({"--tonemap", "filmic", "s.obj"}).find("--tonemap"), std::string::npos);
    EXPECT_NE(usage_error({"--exposure", "lots", "s.obj"}).find("--exposure"), std::string::npos);
    EXPECT_NE(usage_error({"--tonemap", "none", "--exposure", "1", "s.obj"}).find("--exposure"), std::string::npos);
    EXPECT_NE(usage_error({"--aov", "albedo", "--denoise", "s.obj"}).find("--denoise"), std::string::npos);
}

TEST(Options, ThinLens)
{
    const Options o = parse({"--aperture", "0.05", "--focus-distance=3.5", "s.obj"});
    EXPECT_EQ(o.aperture_radius, 0.05f);
    EXPECT_EQ(o.focus_distance, 3.5f);
    const SceneRequest r = scene_request(o);
    EXPECT_EQ(r.camera.aperture_radius, 0.05f);
    EXPECT_EQ(r.camera.focus_distance, 3.5f);
    EXPECT_FALSE(parse({"s.obj"}).aperture_radius);
    EXPECT_NE(usage_error({"--aperture", "-1", "s.obj"}).find("--aperture"), std::string::npos);
    EXPECT_NE(usage_error({"--focus-distance", "0", "s.obj"}).find("--focus-distance"), std::string::npos);
}

TEST(Options, CheckpointsResumeAndAovLayers)
{
    const Options o = parse({"s.obj", "--checkpoint-every", "30", "--resume", "part.exr", "--aovs", "depth,albedo"});
    EXPECT_EQ(o.checkpoint_seconds, 30.0);
    EXPECT_EQ(o.resume_path, "part.exr");
    EXPECT_EQ(o.aovs, (std::vector<AovLayer>{AovLayer::Depth, AovLayer::Albedo}));
    EXPECT_NE(usage_error({"s.obj", "--checkpoint-every", "0"}).find("--checkpoint-every"), std::string::npos);
    EXPECT_NE(usage_error({"s.obj", "--aovs", "depth,"}).find("unknown layer ''"), std::string::npos);
    EXPECT_NE(usage_error({"s.obj", "--aovs", "variance", "--resume", "p.exr"}).find("variance"), std::string::npos);
    EXPECT_NE(usage_error({"s.obj", "--samples", "0:8", "--checkpoint-every", "5"}).find("--samples"),
              std::string::npos);
}

}  // namespace
}  // namespace gc
