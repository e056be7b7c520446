// --noise-threshold (adaptive sampling): parsed into the render settings; bad values and the
// renders it cannot do are UsageErrors that name the option.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "host/app/options.h"
#include "host/util/error.h"

namespace gc {
namespace {

std::string usage_error(const std::vector<std::string>& args)
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

TEST(NoiseThresholdOption, ParsesWithTheCap)
{
    EXPECT_EQ(parse_options({"scene.obj"}).render.noise_threshold, 0.0);  // off by default
    const Options o = parse_options({"scene.obj", "--noise-threshold", "0.02", "--spp", "1024"});
    EXPECT_FLOAT_EQ(float(o.render.noise_threshold), 0.02f);
    EXPECT_EQ(o.render.spp, 1024u);
    EXPECT_FLOAT_EQ(float(parse_options({"scene.obj", "--noise-threshold=0.5"}).render.noise_threshold), 0.5f);
}

TEST(NoiseThresholdOption, BadValuesNameTheOption)
{
    for (const char* bad : {"0", "-0.1", "abc", "nan", "inf", ""}) {
        const std::string message = usage_error({"scene.obj", "--noise-threshold", bad});
        std::printf("  --noise-threshold '%s': %s\n", bad, message.c_str());
        EXPECT_NE(message.find("--noise-threshold"), std::string::npos) << message;
    }
    EXPECT_NE(usage_error({"scene.obj", "--noise-threshold"}).find("--noise-threshold needs a value"),
              std::string::npos);
}

TEST(NoiseThresholdOption, RefusesWhatItCannotRender)
{
    const std::string whitted = usage_error({"scene.obj", "--noise-threshold", "0.1", "--integrator", "whitted"});
    EXPECT_NE(whitted.find("--noise-threshold needs --integrator path"), std::string::npos) << whitted;
    const std::string aov = usage_error({"scene.obj", "--aov", "albedo", "--noise-threshold", "0.1"});
    EXPECT_NE(aov.find("--noise-threshold needs --integrator path"), std::string::npos) << aov;
    const std::string partial = usage_error({"scene.obj", "--noise-threshold", "0.1", "--samples", "0:64"});
    EXPECT_NE(partial.find("--noise-threshold cannot render a partial image (--samples)"), std::string::npos)
        << partial;
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"scene.obj", "--noise-threshold", "0.1", "--resume", "a.partial.exr"},
          std::vector<std::string>{"scene.obj", "--noise-threshold", "0.1", "--checkpoint-every", "60"}}) {
        const std::string message = usage_error(args);
        EXPECT_NE(message.find("--noise-threshold cannot go with --resume or --checkpoint-every"), std::string::npos)
            << message;
    }
}

}  // namespace
}  // namespace gc
