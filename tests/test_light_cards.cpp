// Light cards (kernels/light_card.h, the bake in baker/src/light_card, the runtime's textured rectangle in
// kernels/textured_light.h): a constant card against the uniform rectangle light, the sweep roughness x
// distance x view against the fp64 brute force over the textured rectangle (table printed), the inverse
// square far away, finite results where the geometry degenerates, OpenCL against TBB for the bake and the
// runtime, and the file through the runtime loader and the command line.
#include "cli_runner.h"
#include "light_card_test_support.h"

#include <iblbake/baker/light_card.h>
#include <iblbake/core/error.h>
#include <iblbake/opencl/executor.h>
#include <iblbake/runtime/runtime_light_card.h>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace ibl;
using namespace ibl::test;
namespace fs = std::filesystem;

const float kRoughness[] = {0.1f, 0.3f, 0.6f, 1.0f};
const float kDistance[] = {1.0f, 3.0f, 10.0f};
const float kElevation[] = {0.0f, 1.0f};             // radians: on the axis, and 57 degrees off it
const float kViewAngle[] = {0.0f, 0.5f, 1.0f, 1.4f}; // radians: 0, 29, 57, 80 degrees
const glm::vec3 kTargets[] = {{0.0f, 0.0f, 0.0f}, {0.3f, -0.2f, 0.0f}}; // the centre, and off it

std::vector<ShadingPoint> cellPoints(float roughness, float distance) {
    std::vector<ShadingPoint> points;
    for (const glm::vec3& target : kTargets)
        for (float elevation : kElevation)
            for (float view : kViewAngle)
                points.push_back(sweepPoint(distance, elevation, 0.6f, view, roughness, target));
    return points;
}

bool isGrazing(std::size_t point) {
    return kViewAngle[point % std::size(kViewAngle)] > 1.2f;
}

// A constant card of any colour gives the uniform rectangle light of that colour: the card's lookups are
// normalized (sum T w / sum w), so only float rounding remains.
TEST(LightCards, ConstantCardIsTheUniformRectangle) {
    const glm::vec3 colour(1.0f, 0.5f, 0.25f);
    const ImageRGBA emission = constantEmission(32, colour);
    const LightCardData card = bakeCard(emission, Executor::cpu());
    AreaLight uniform = unitRectangle();
    uniform.color = glm::vec3(emission.pixels.front()); // the normalized colour: luminance 1
    double worst = 0.0;
    for (float roughness : kRoughness)
        for (float distance : kDistance) {
            const std::vector<ShadingPoint> points = cellPoints(roughness, distance);
            const std::vector<AreaLightResult> textured =
                shadeTexturedLightCpu(unitRectangle(), card, points);
            const std::vector<AreaLightResult> reference = shadeAreaLightCpu(uniform, points);
            for (std::size_t i = 0; i < points.size(); ++i) {
                worst = std::max(worst, channelError(textured[i].diffuse, reference[i].diffuse));
                worst = std::max(worst, channelError(textured[i].specular, reference[i].specular));
            }
        }
    std::printf("constant card vs uniform rectangle: worst channel relative difference %.3g\n", worst);
    EXPECT_LT(worst, 1e-2);
}

// Mean relative errors of one (roughness, distance) cell of the sweep.
struct CellError {
    double diffuse = 0.0, diffuseChannel = 0.0;   // luminance; the worst channel's
    double specular = 0.0, specularChannel = 0.0; // views up to 57 degrees
    double specularGrazing = 0.0;                 // 80 degrees
    double uniformSpecular = 0.0;                 // the uniform light's own error at the same views
    double reference = 0.0; // the reference's own estimate, relative, the cell's largest
};

CellError sweepCell(const LightCardData& card, const ImageRGBA& emission, float roughness, float distance) {
    const std::vector<ShadingPoint> points = cellPoints(roughness, distance);
    RuntimeOptions options;
    options.energyCompensation = false;
    const AreaLight light = unitRectangle();
    const std::vector<AreaLightResult> runtime = shadeTexturedLightCpu(light, card, points, options);
    const std::vector<AreaReference> reference =
        renderTexturedLightReference(light, emission, points, options);
    // The uniform light of the card's mean colour against its own brute force: what the representative
    // point costs before any texture.
    const std::vector<AreaLightResult> uniform = shadeAreaLightCpu(light, points, options);
    const std::vector<AreaReference> uniformReference = renderAreaLightReference(light, points, options);
    CellError e;
    int grazing = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const glm::dvec3 rd = reference[i].value.diffuse, rs = reference[i].value.specular;
        EXPECT_GT(glm::dot(rd, kLuma), 0.0);
        EXPECT_GT(glm::dot(rs, kLuma), 0.0);
        e.diffuse += lumaError(runtime[i].diffuse, rd);
        e.diffuseChannel += channelError(runtime[i].diffuse, rd);
        const double specular = lumaError(runtime[i].specular, rs);
        if (isGrazing(i)) {
            e.specularGrazing += specular;
            ++grazing;
        } else {
            e.specular += specular;
            e.specularChannel += channelError(runtime[i].specular, rs);
            e.uniformSpecular += lumaError(uniform[i].specular, uniformReference[i].value.specular);
        }
        e.reference = std::max({e.reference, glm::dot(reference[i].diffuseError, kLuma) / glm::dot(rd, kLuma),
                                glm::dot(reference[i].specularError, kLuma) / glm::dot(rs, kLuma)});
    }
    const double n = double(points.size()), front = n - grazing;
    e.diffuse /= n, e.diffuseChannel /= n;
    e.specular /= front, e.specularChannel /= front, e.uniformSpecular /= front;
    e.specularGrazing /= grazing;
    return e;
}

// The sweep of issue 15 for the textured rectangle: 4 roughnesses x 3 distances x 2 reflection targets x
// 2 elevations x 4 views, 64 x 64 card, 8 diffuse layers. Bounds: this table's measurement with margin
// (the README's table). Diffuse (exact for a constant card) 4.5% / 2.5% / 1% at 1 / 3 / 10 light sizes,
// the worst channel 16% / 12% / 5%: the lookup's kernel is the light seen from the point at the same height
// above p_d, facing it, so a tilted or oblique receiver's own weighting (its cosine, 1 / d^2 across the
// light) is lost; the red and green ramps (10:1) show it. Specular up to 57 degrees 12%: the card adds little
// to the representative point's own error (the uniform light's column); at 80 degrees (the representative
// point's known failure, Frostbite 4.7.5) 45%, 70% at 1 light size.
TEST(LightCards, SweepAgainstTheBruteForce) {
    const ImageRGBA emission = texturedEmission(64);
    const LightCardData card = bakeCard(emission, Executor::cpu());
    std::printf("| r | d | diffuse | diffuse worst channel | specular <= 57 deg | specular worst channel | "
                "uniform light's specular | specular 80 deg | reference error |\n"
                "|---|---|---|---|---|---|---|---|---|\n");
    for (float roughness : kRoughness)
        for (float distance : kDistance) {
            const CellError e = sweepCell(card, emission, roughness, distance);
            std::printf("| %.1f | %.0f | %.2f%% | %.2f%% | %.2f%% | %.2f%% | %.2f%% | %.2f%% | %.3f%% |\n",
                        roughness, distance, 100.0 * e.diffuse, 100.0 * e.diffuseChannel, 100.0 * e.specular,
                        100.0 * e.specularChannel, 100.0 * e.uniformSpecular, 100.0 * e.specularGrazing,
                        100.0 * e.reference);
            SCOPED_TRACE("r " + std::to_string(roughness) + " d " + std::to_string(distance));
            EXPECT_LT(e.reference, 0.002);
            EXPECT_LT(e.diffuse, distance < 2.0f ? 0.045 : distance < 5.0f ? 0.025 : 0.01);
            EXPECT_LT(e.diffuseChannel, distance < 2.0f ? 0.16 : distance < 5.0f ? 0.12 : 0.05);
            EXPECT_LT(e.specular, 0.12);
            EXPECT_LT(e.specularGrazing, distance > 1.0f ? 0.45 : 0.70);
        }
}

// Far away the textured light is the point light of its luminous power: E d^2 stays the same and equals
// the uniform light's (the diffuse layers converge to the card's mean, which is luminance 1).
TEST(LightCards, InverseSquareFarAway) {
    const ImageRGBA emission = texturedEmission(32);
    const LightCardData card = bakeCard(emission, Executor::cpu());
    RuntimeOptions lambert;
    lambert.specular = false;
    std::vector<ShadingPoint> points;
    for (float d : {10.0f, 20.0f, 40.0f, 100.0f})
        points.push_back(sweepPoint(d, 0.3f, 0.6f, 0.0f, 0.5f, glm::vec3(0.0f)));
    const std::vector<AreaLightResult> textured =
        shadeTexturedLightCpu(unitRectangle(), card, points, lambert);
    const std::vector<AreaLightResult> uniform = shadeAreaLightCpu(unitRectangle(), points, lambert);
    const std::vector<AreaReference> reference =
        renderTexturedLightReference(unitRectangle(), emission, points, lambert);
    for (std::size_t i = 0; i < points.size(); ++i) {
        const double d2 = glm::dot(points[i].position, points[i].position);
        const double e = glm::dot(glm::dvec3(textured[i].diffuse), kLuma) * d2;
        SCOPED_TRACE("d^2 " + std::to_string(d2));
        EXPECT_NEAR(e / (glm::dot(glm::dvec3(uniform[i].diffuse), kLuma) * d2), 1.0, 1e-2);
        EXPECT_NEAR(e / (glm::dot(reference[i].value.diffuse, kLuma) * d2), 1.0, 1e-2);
        if (i > 0) {
            const double d2Previous = glm::dot(points[i - 1].position, points[i - 1].position);
            EXPECT_NEAR(glm::dot(glm::dvec3(textured[i - 1].diffuse), kLuma) * d2Previous / e, 1.0, 1e-2);
        }
    }
}

// Degenerate geometry: finite, non-negative results everywhere, zero where nothing is lit (behind the
// light, on its plane), for the textured light as for the uniform one.
TEST(LightCards, HardCasesAreFinite) {
    const LightCardData card = bakeCard(texturedEmission(16), Executor::cpu(), 2);
    const glm::vec3 up(0.0f, 0.0f, 1.0f), white(1.0f);
    std::vector<ShadingPoint> points;
    std::vector<bool> unlit;
    auto add = [&](glm::vec3 position, glm::vec3 normal, glm::vec3 view, float roughness, bool dark) {
        points.push_back(makeShadingPoint(position, normal, view, white, 0.0f, roughness));
        unlit.push_back(dark);
    };
    for (float roughness : {0.0f, 0.05f, 1.0f}) {
        add({0.3f, 0.0f, 0.0f}, up, up, roughness, true);                  // on the light
        add({2.0f, 0.0f, 0.0f}, up, up, roughness, true);                  // on its plane, beside it
        add({2.0f, 0.0f, 0.0f}, {-1.0f, 0.0f, 0.0f}, up, roughness, true); // ... facing it edge-on
        add({0.0f, 0.0f, -1.0f}, -up, -up, roughness, true);               // behind it
        add({0.0f, 0.0f, -1.0f}, up, up, roughness, true);                 // behind it, facing its back
        add({0.0f, 0.0f, 1.0f}, {1.0f, 0.0f, 0.0f}, up, roughness,
            false); // grazing: the light on the horizon
        add({0.0f, 0.0f, 1.0f}, -up, {1.0f, 0.0f, 0.0f}, roughness, false); // grazing view
        add({0.0f, 0.0f, 1.0f}, -up, up, roughness, false);                 // view from behind the surface
        add({0.4f, 0.5f, 1e-4f}, -up, -up, roughness, false); // almost on the light, at its edge
        add({5.0f, 0.0f, 1e-3f}, {-1.0f, 0.0f, 0.0f}, up, roughness, false); // far along the plane
        add({0.0f, 0.0f, 1.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, roughness, false); // zero vectors
    }
    for (DiffuseModel model : {DiffuseModel::Lambert, DiffuseModel::Disney}) {
        RuntimeOptions options;
        options.diffuseModel = model;
        const std::vector<AreaLightResult> r = shadeTexturedLightCpu(unitRectangle(), card, points, options);
        for (std::size_t i = 0; i < points.size(); ++i) {
            SCOPED_TRACE("point " + std::to_string(i % 11) + " r " +
                         std::to_string(points[i].perceptualRoughness));
            for (int c = 0; c < 3; ++c)
                for (float v : {r[i].diffuse[c], r[i].specular[c]}) {
                    EXPECT_TRUE(std::isfinite(v));
                    EXPECT_GE(v, 0.0f);
                    if (unlit[i]) {
                        EXPECT_EQ(v, 0.0f);
                    }
                }
        }
    }
}

// The bake on OpenCL against the same work-item on TBB, every level and layer; and the runtime likewise.
TEST(LightCards, OpenCLMatchesCpu) {
    std::ostringstream warnings;
    Executor executor = Executor::create(Backend::Auto, "", warnings);
    if (!executor.usesOpenCL()) GTEST_SKIP() << "no OpenCL device";
    const ImageRGBA emission = texturedEmission(64);
    const LightCardData cpu = bakeCard(emission, Executor::cpu());
    const LightCardData cl = bakeCard(emission, executor);
    ASSERT_EQ(cpu.texels.size(), cl.texels.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < cpu.texels.size(); ++i)
        worst = std::max(worst, double(std::abs(cpu.texels[i] - cl.texels[i])) /
                                    std::max(1e-3f, std::abs(cpu.texels[i])));
    std::printf("card bake: OpenCL vs CPU over %zu floats: max relative difference %.3g\n", cpu.texels.size(),
                worst);
    EXPECT_LT(worst, 1e-4);

    std::vector<ShadingPoint> points;
    for (float roughness : kRoughness)
        for (float distance : kDistance)
            for (const ShadingPoint& p : cellPoints(roughness, distance))
                points.push_back(p);
    RuntimeOptions options;
    options.diffuseModel = DiffuseModel::Disney;
    const std::vector<AreaLightResult> a = shadeTexturedLightCpu(unitRectangle(), cpu, points, options);
    const std::vector<AreaLightResult> b =
        shadeTexturedLightOpenCL(executor.cl(), unitRectangle(), cpu, points, options);
    double worstShade = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double x = a[i].diffuse[c] + a[i].specular[c], y = b[i].diffuse[c] + b[i].specular[c];
            worstShade = std::max(worstShade, std::abs(x - y) / std::max(1e-3, std::abs(x)));
        }
    std::printf("textured light: OpenCL vs CPU over %zu points: max relative difference %.3g\n",
                points.size(), worstShade);
    EXPECT_LT(worstShade, 2e-3);
}

// An 8-bit PNG: the ramp of `texturedEmission`'s red channel, a grey ramp; written as sRGB code values.
void writePng(const fs::path& file, int width, int height) {
    std::vector<unsigned char> pixels(std::size_t(width) * height * 3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c)
                pixels[(std::size_t(y) * width + x) * 3 + c] =
                    (unsigned char)(40 + (200 * x) / width + 10 * c);
    auto out = OIIO::ImageOutput::create(file.string());
    ASSERT_TRUE(out);
    ASSERT_TRUE(out->open(file.string(), OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::UINT8)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
    out->close();
}

// The flow of `iblbake lightcard` in-process, read back by the runtime loader: levels, layers, the mapping's
// keys; the texture decoded as sRGB and normalized to mean luminance 1; files that are no card refused.
TEST(LightCards, FileReadBackByTheRuntimeLoader) {
    const fs::path dir = ibl::test::freshTempDir("light_card_file");
    writePng(dir / "window.png", 48, 24);
    LightCardSettings settings;
    settings.size = 16;
    settings.diffuseLayers = 4;
    settings.format = Ktx2Format::RGBA32F;
    bakeLightCardFile(dir / "window.png", dir / "card.ktx2", settings, Executor::cpu());
    const LightCardData card = loadLightCard(dir / "card.ktx2");
    EXPECT_EQ(card.layout.width, 16u);
    EXPECT_EQ(card.layout.levelCount, 5u);
    EXPECT_EQ(card.layout.diffuseLayers, 4u);
    EXPECT_FLOAT_EQ(card.layout.aspect, 2.0f);
    EXPECT_FLOAT_EQ(card.layout.maxDistance, lightCardMaxDistance());
    // Level 0 layer 0 is the emission: mean luminance 1, and sRGB-decoded (the left edge's code 40-60 is
    // far darker than linear 40/255 relative to the right edge's 240-260).
    double sum = 0.0;
    for (int i = 0; i < 16 * 16; ++i)
        sum +=
            glm::dot(glm::dvec3(card.texels[4 * i], card.texels[4 * i + 1], card.texels[4 * i + 2]), kLuma);
    EXPECT_NEAR(sum / 256.0, 1.0, 1e-4);
    const double left = card.texels[0], right = card.texels[4 * 15];
    EXPECT_LT(left / right, 0.05); // sRGB: (45/245)^2.4 ~ 0.017; linear would be 0.18
    // The diffuse layers far away converge to the mean: the last layer (r_max) is within 1% of it.
    const std::uint32_t last = lightCardOffset(card.layout, 0, card.layout.diffuseLayers);
    for (int i = 0; i < 16 * 16; ++i)
        EXPECT_NEAR(glm::dot(glm::dvec3(card.texels[last + 4 * i], card.texels[last + 4 * i + 1],
                                        card.texels[last + 4 * i + 2]),
                             kLuma),
                    1.0, 0.01);

    // Not a card: a 2D KTX2 without the keys, and a card whose layers disagree with its keys.
    ImageRGBA image(4, 4);
    writeKtx2Image(dir / "lut.ktx2", image, Ktx2Format::RGBA32F, {{"iblbake.product", "dfg-lut"}});
    try {
        loadLightCard(dir / "lut.ktx2");
        ADD_FAILURE() << "a LUT was read as a light card";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("lut.ktx2"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("light-card"), std::string::npos) << e.what();
    }
    Ktx2Image stored = readKtx2(dir / "card.ktx2");
    Ktx2KeyValues keys(stored.keyValues.begin(), stored.keyValues.end());
    keys.erase(
        std::remove_if(keys.begin(), keys.end(), [](const auto& kv) { return kv.first == "KTXwriter"; }),
        keys.end());
    for (auto& [key, value] : keys)
        if (key == "iblbake.cardDiffuseLayers") value = "5";
    writeKtx2Array(dir / "bad.ktx2", stored.levels, Ktx2Format::RGBA32F, keys);
    try {
        loadLightCard(dir / "bad.ktx2");
        ADD_FAILURE() << "a card with the wrong layer count was read";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("bad.ktx2: 5 layers"), std::string::npos) << e.what();
    }
    fs::remove_all(dir);
}

// Bad input on the command line: a one-line error naming the cause, a non-zero exit, no output file.
TEST(LightCards, CommandLineRefusesBadInput) {
    const fs::path dir = ibl::test::freshTempDir("light_card_cli");
    writePng(dir / "window.png", 8, 8);
    const fs::path out = dir / "card.ktx2";
    ibl::test::CliRun ok = ibl::test::runCli("lightcard " + (dir / "window.png").string() +
                                             " --size 8 --layers 3 --backend cpu -o " + out.string());
    EXPECT_EQ(ok.exitCode, 0) << ok.err;
    EXPECT_TRUE(fs::exists(out));
    fs::remove(out);
    struct Case {
        std::string args, message;
    } cases[] = {{"--size 12", "power of two"},
                 {"--layers 1", "diffuse layer count 1"},
                 {"--format rgb8", "'rgb8' is not one of"}};
    for (const Case& c : cases) {
        ibl::test::CliRun r = ibl::test::runCli("lightcard " + (dir / "window.png").string() + " " + c.args +
                                                " --backend cpu -o " + out.string());
        EXPECT_NE(r.exitCode, 0) << c.args;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << ": " << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_FALSE(fs::exists(out)) << c.args;
    }
    ibl::test::CliRun missing =
        ibl::test::runCli("lightcard " + (dir / "none.png").string() + " --backend cpu -o " + out.string());
    EXPECT_NE(missing.exitCode, 0);
    EXPECT_NE(missing.err.find("none.png"), std::string::npos) << missing.err;
    EXPECT_FALSE(fs::exists(out));
    fs::remove_all(dir);
}

} // namespace
