// iblbake gltf: the exported EXT_lights_image_based / KHR_lights_punctual glTF against the bake it came
// from, numerically (conventions in baker/include/baker/iblbake/baker/gltf_ibl.h), and its refusals of bad
// input.
#include "bake_dir_support.h"

#include <cube.h>
#include <iblbake/baker/calibration.h>
#include <iblbake/baker/sh.h>
#include <iblbake/baker/sun.h>
#include <iblbake/ktx2/ktx2.h>
#include <iblbake/ktx2/storage_scale.h>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <glm/geometric.hpp>

namespace fs = std::filesystem;
using ibl::test::CliRun;
using ibl::test::runCli;

namespace {

constexpr double kPi = 3.14159265358979323846;

nlohmann::json readJson(const fs::path& path) {
    std::ifstream in(path);
    return nlohmann::json::parse(in);
}

ibl::ShRgb shFromJson(const nlohmann::json& a) {
    ibl::ShRgb sh{};
    for (std::size_t i = 0; i < 9; ++i)
        sh[i] = glm::dvec3(a[i][0].get<double>(), a[i][1].get<double>(), a[i][2].get<double>());
    return sh;
}

// The irradiance as Babylon.js reads the coefficients, written out here rather than taken from the
// library: SphericalHarmonics.FromArray in its basis (Condon-Shortley signs on (1,-1), (1,1), (2,-1),
// (2,1)), evaluated at the normal in Babylon's left-handed frame, where glTF (x, y, z) is (-x, y, z).
glm::dvec3 irradianceAsBabylonReadsIt(const ibl::ShRgb& e, const glm::dvec3& gltfNormal) {
    const double k0 = 0.5 * std::sqrt(1.0 / kPi), k1 = std::sqrt(3.0 / (4.0 * kPi));
    const double k2 = 0.5 * std::sqrt(15.0 / kPi), k20 = 0.25 * std::sqrt(5.0 / kPi);
    const double k22 = 0.25 * std::sqrt(15.0 / kPi);
    const double x = -gltfNormal.x, y = gltfNormal.y, z = gltfNormal.z;
    return e[0] * k0 - e[1] * (k1 * y) + e[2] * (k1 * z) - e[3] * (k1 * x) + e[4] * (k2 * x * y) -
           e[5] * (k2 * y * z) + e[6] * (k20 * (3.0 * z * z - 1.0)) - e[7] * (k2 * x * z) +
           e[8] * (k22 * (x * x - y * y));
}

// Babylon.js's fromRGBD (the extension's reference loader), from the raw 8-bit PNG: rgb^2.2 / a.
std::vector<glm::dvec3> decodeRgbdPng(const fs::path& path, int& width) {
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(path.string(), &config);
    EXPECT_TRUE(in) << path;
    if (!in) return {};
    width = in->spec().width;
    EXPECT_EQ(in->spec().nchannels, 4);
    std::vector<unsigned char> px(std::size_t(width) * in->spec().height * 4);
    EXPECT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT8, px.data()));
    std::vector<glm::dvec3> out;
    for (std::size_t i = 0; i < px.size(); i += 4) {
        const double d = px[i + 3] / 255.0;
        out.emplace_back(std::pow(px[i] / 255.0, 2.2) / d, std::pow(px[i + 1] / 255.0, 2.2) / d,
                         std::pow(px[i + 2] / 255.0, 2.2) / d);
    }
    return out;
}

// The largest error RGBD can make on channel value v (already divided by the intensity) of a texel whose
// brightest channel is maxRgb: D = floor(255 / maxRgb) / 255 is exact, g = (v D)^(1/2.2) is rounded to
// 1/255, so the decoded value lies between the neighbours (g -+ 0.5/255)^2.2 / D.
double rgbdBound(double v, double maxRgb) {
    const double d =
        std::clamp(std::floor(std::max(255.0 / std::max(maxRgb, 1e-7), 1.0)), 1.0, 255.0) / 255.0;
    const double g = std::pow(std::min(v * d, 1.0), 1.0 / 2.2), h = 0.5 / 255.0;
    return (std::pow(std::min(g + h, 1.0), 2.2) - std::pow(std::max(g - h, 0.0), 2.2)) / d * 1.0001 + 1e-9;
}

// The KTX2's texels in radiance: what intensity x decoded image must give (the exporter folds the file's
// storage scale into the intensity).
ibl::Ktx2Image radianceOf(ibl::Ktx2Image ktx) {
    ibl::unscaleKtx2Texels(ktx);
    return ktx;
}

// Level 0 of a chain that kept the extracted sun (iblbake.sunInLevel0), without it: the residual the
// exporter writes (the same detection on the same pixels, as `iblbake gltf` runs it).
ibl::Ktx2Image withResidualLevel0(ibl::Ktx2Image ktx) {
    ibl::CubeMap level0(int(ktx.pixelWidth));
    for (int f = 0; f < 6; ++f)
        level0.faces[f] = ktx.levels[0][std::size_t(f)];
    ibl::SunDetectSettings settings;
    settings.luminanceWeights = ibl::workingLuminanceWeights(ktx.keyValues.at("iblbake.colorSpace"));
    settings.maxSolidAngle = std::stod(ktx.keyValues.at("iblbake.sunMaxSolidAngle"));
    const ibl::SunDetection detection = ibl::detectSun(level0, settings);
    EXPECT_TRUE(detection.found) << detection.reason;
    ibl::extractSun(level0, detection, settings.luminanceWeights);
    for (int f = 0; f < 6; ++f)
        ktx.levels[0][std::size_t(f)] = level0.faces[f];
    return ktx;
}

// Every texel of level `level` of the export against level `ktxLevel` of the KTX2 (in radiance); returns the
// largest relative error (for the report) and fails on any texel outside the RGBD bound.
// Where Babylon.js shows texel (x, row) of exported face f of an n-texel level, as our (face, x, y): it
// uploads the image's rows in the opposite order, and shows cube direction c at glTF (-c.x, c.y, c.z).
ibl::CubeCoord ourTexelShownAt(int face, int x, int row, int n) {
    const ibl::vec3 c = ibl::cubeTexelDirection(face, uint32_t(x), uint32_t(n - 1 - row), uint32_t(n));
    return ibl::cubeCoordFromDirection(ibl::vec3(-c.x, c.y, c.z));
}

// Every texel of level `level` of the export against level `ktxLevel` of the KTX2, where Babylon shows
// it; returns the largest relative error (for the report) and fails on any texel outside the RGBD bound.
// The file stores (value / intensity)^(1 / 2.2) (Babylon raises the decoded texel to 2.2: the babylon
// profile's decodeGamma), which is what the RGBD bound applies to.
double compareLevel(const fs::path& dir, const nlohmann::json& light, int level, const ibl::Ktx2Image& ktx,
                    int ktxLevel) {
    const double intensity = light.at("intensity").get<double>();
    const char* faces[6] = {"px", "nx", "py", "ny", "pz", "nz"};
    double worst = 0.0;
    for (int f = 0; f < 6; ++f) {
        int width = 0;
        const std::vector<glm::dvec3> decoded =
            decodeRgbdPng(dir / ("scene_specular_" + std::to_string(level) + "_" + faces[f] + ".png"), width);
        const ibl::ImageRGBA& ref = ktx.levels[std::size_t(ktxLevel)][std::size_t(f)];
        EXPECT_EQ(width, ref.width);
        if (decoded.size() != ref.pixels.size()) return 1.0;
        for (std::size_t i = 0; i < decoded.size(); ++i) {
            const ibl::CubeCoord at =
                ourTexelShownAt(f, int(i % std::size_t(width)), int(i / std::size_t(width)), width);
            const ibl::ImageRGBA& face = ktx.levels[std::size_t(ktxLevel)][std::size_t(at.face)];
            const std::size_t j =
                std::size_t(at.t * float(width)) * std::size_t(width) + std::size_t(at.s * float(width));
            const glm::dvec3 v =
                glm::pow(glm::dvec3(glm::vec3(face.pixels[j])) / intensity, glm::dvec3(1.0 / 2.2));
            const double maxRgb = std::max({v.x, v.y, v.z});
            for (int c = 0; c < 3; ++c) {
                if (std::abs(decoded[i][c] - v[c]) > rgbdBound(v[c], maxRgb)) {
                    ADD_FAILURE() << "level " << level << " face " << f << " texel " << i << " channel " << c
                                  << ": decoded " << decoded[i][c] << ", baked " << v[c];
                    return worst;
                }
                if (maxRgb > 1.0) worst = std::max(worst, std::abs(decoded[i][c] - v[c]) / maxRgb);
            }
        }
    }
    return worst;
}

class GltfExport : public ::testing::Test {
  protected:
    void SetUp() override {
        bake = ibl::test::makeBakeDir("gltf_bake");
        out = ibl::test::freshTempDir("gltf_out");
        CliRun r =
            runCli("gltf " + bake.string() + " -o " + (out / "scene.gltf").string() + " --quality draft");
        ASSERT_EQ(r.exitCode, 0) << r.err;
        gltf = readJson(out / "scene.gltf");
        light = gltf["extensions"]["EXT_lights_image_based"]["lights"][0];
    }
    void TearDown() override {
        fs::remove_all(bake);
        fs::remove_all(out);
    }
    fs::path bake, out;
    nlohmann::json gltf, light;
};

} // namespace

TEST_F(GltfExport, IrradianceCoefficientsReproduceOurShIrradiance) {
    const ibl::ShRgb ours = shFromJson(readJson(bake / "diffuse.json")["sh"]["irradiance"]);
    ibl::ShRgb fromGltf = shFromJson(light["irradianceCoefficients"]);
    const double intensity = light["intensity"].get<double>();
    for (glm::dvec3& c : fromGltf)
        c *= intensity * intensity; // Babylon's loader scales them by the intensity, its shader again
    const glm::dvec3 directions[] = {{0, 1, 0},  {0, -1, 0}, {1, 0, 0},        {-1, 0, 0},        {0, 0, 1},
                                     {0, 0, -1}, {1, 1, 1},  {-0.3, 0.8, 0.5}, {0.6, -0.2, -0.77}};
    for (glm::dvec3 n : directions) {
        n = glm::normalize(n);
        const glm::dvec3 expected = ibl::evalPrescaledSH(ours, n),
                         got = irradianceAsBabylonReadsIt(fromGltf, n);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(got[c], expected[c], 1e-5 * std::abs(expected[c]))
                << "n = " << n.x << " " << n.y << " " << n.z << " channel " << c;
    }
}

TEST_F(GltfExport, StructureFollowsTheExtension) {
    EXPECT_EQ(gltf["asset"]["version"], "2.0");
    EXPECT_EQ(gltf["scenes"][0]["extensions"]["EXT_lights_image_based"]["light"], 0);
    EXPECT_EQ(light["rotation"], nlohmann::json::array({0.0, 0.0, 0.0, 1.0}));
    EXPECT_EQ(light["specularImageSize"], 32);
    // The chain is re-filtered 32..16 (2 levels) to the roughness Babylon reads at each level.
    ASSERT_EQ(light["specularImages"].size(), 2u);
    for (const auto& level : light["specularImages"]) {
        ASSERT_EQ(level.size(), 6u);
        for (const auto& image : level) {
            const std::string uri = gltf["images"][image.get<std::size_t>()]["uri"];
            EXPECT_TRUE(fs::exists(out / uri)) << uri;
        }
    }
    EXPECT_EQ(gltf["images"].size(), 12u);
}

// The bake's rgba16f chain is stored with a storage scale and keeps the sun in level 0: the export's first
// level is level 0's residual, in radiance.
TEST_F(GltfExport, FirstSpecularLevelRoundTripsLdLevel0) {
    const ibl::Ktx2Image ktx = ibl::readKtx2(bake / "specular.ktx2");
    EXPECT_LT(ibl::ktx2StorageScale(ktx), 1.0);
    ASSERT_EQ(ktx.keyValues.at("iblbake.sunInLevel0"), "true");
    const ibl::Ktx2Image radiance = withResidualLevel0(radianceOf(ktx));
    const double worst = compareLevel(out, light, 0, radiance, 0);
    std::printf(
        "level 0: largest RGBD error %.4f%% of the texel's brightest channel (before the power 2.2)\n",
        100.0 * worst);
    // The brightest exported channel (level 0's: the others are its filtered copies) decodes to 255^2.2.
    float brightest = 0.0f;
    for (const ibl::ImageRGBA& face : radiance.levels[0])
        for (const glm::vec4& p : face.pixels)
            brightest = std::max({brightest, p.r, p.g, p.b});
    EXPECT_NEAR(light["intensity"].get<double>() * std::pow(255.0, 2.2), brightest, 1e-5 * brightest);
}

TEST_F(GltfExport, SunIsADirectionalLightWithTheSameIlluminance) {
    const ibl::DiskLight sun = [&] {
        std::ifstream in(bake / "sun.json");
        return ibl::diskLightFromJson(std::string(std::istreambuf_iterator<char>(in), {}));
    }();
    const nlohmann::json& punctual = gltf["extensions"]["KHR_lights_punctual"]["lights"][0];
    EXPECT_EQ(punctual["type"], "directional");
    glm::dvec3 color(punctual["color"][0].get<double>(), punctual["color"][1].get<double>(),
                     punctual["color"][2].get<double>());
    EXPECT_DOUBLE_EQ(std::max({color.r, color.g, color.b}), 1.0);
    const glm::dvec3 rgbIlluminance = color * punctual["intensity"].get<double>();
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(rgbIlluminance[c], sun.illuminance * sun.color[c], 1e-9 * sun.illuminance);
    // The node's rotation turns -Z (where a directional light shines) away from the sun.
    const nlohmann::json& node = gltf["nodes"][gltf["scenes"][0]["nodes"][0].get<std::size_t>()];
    EXPECT_EQ(node["extensions"]["KHR_lights_punctual"]["light"], 0);
    const glm::dvec3 q(node["rotation"][0].get<double>(), node["rotation"][1].get<double>(),
                       node["rotation"][2].get<double>());
    const double w = node["rotation"][3].get<double>();
    const glm::dvec3 v(0.0, 0.0, -1.0);
    const glm::dvec3 rotated = v + 2.0 * glm::cross(q, glm::cross(q, v) + w * v);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(rotated[c], -sun.direction[c], 1e-9);
}

// Whatever mapping the bake has (here linear, the extension's m / (N - 1)), the export is re-filtered so
// that level m holds the roughness stock Babylon.js reads there (the babylon profile), recorded in the
// light's extras; level 0 stays the bake's (the unconvolved source).
TEST(GltfExportLevels, LevelsHoldTheRoughnessBabylonReads) {
    const fs::path bake = ibl::test::makeBakeDir("gltf_linear", "--mip-mapping linear");
    const fs::path out = ibl::test::freshTempDir("gltf_linear_out");
    CliRun r =
        runCli("gltf " + bake.string() + " -o " + (out / "scene.gltf").string() + " --min-face-size 4");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("refilter 4 levels 32..4 px"), std::string::npos) << r.out;
    const nlohmann::json gltf = readJson(out / "scene.gltf");
    const nlohmann::json& light = gltf["extensions"]["EXT_lights_image_based"]["lights"][0];
    ASSERT_EQ(light["specularImages"].size(), 4u);
    EXPECT_EQ(light["extras"]["iblbake.profile"], "babylon");
    // alphaG = 32^(m/3 - 1), r = sqrt(alphaG - 0.0005): 0, 0.1574, 0.3149, 0.9997 (level 0: the source).
    std::string expected;
    for (double alphaG : {0.0, std::pow(32.0, -2.0 / 3.0), std::pow(32.0, -1.0 / 3.0), 1.0})
        expected += (expected.empty() ? "" : ", ") +
                    nlohmann::json(float(alphaG > 0 ? std::sqrt(alphaG - 0.0005) : 0.0)).dump();
    EXPECT_EQ(light["extras"]["iblbake.levelRoughness"], expected);
    compareLevel(out, light, 0, withResidualLevel0(radianceOf(ibl::readKtx2(bake / "specular.ktx2"))), 0);
    fs::remove_all(bake);
    fs::remove_all(out);
}

// In 32-bit floats the bake's level 0 keeps the extracted sun (iblbake.sunInLevel0); the glTF carries the
// sun as the KHR light, so its first specular image must be the residual, not count the sun twice.
TEST(GltfExportSunInLevel0, FirstImageIsTheResidual) {
    const fs::path bake = ibl::test::makeBakeDir("gltf_sun_level0", "--mip-mapping linear --format rgba32f");
    const fs::path out = ibl::test::freshTempDir("gltf_sun_level0_out");
    const ibl::Ktx2Image ktx = ibl::readKtx2(bake / "specular.ktx2");
    ASSERT_EQ(ktx.keyValues.at("iblbake.sunInLevel0"), "true");
    CliRun r = runCli("gltf " + bake.string() + " -o " + (out / "scene.gltf").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    float peakLevel0 = 0.0f, peakLevel1 = 0.0f;
    for (int f = 0; f < 6; ++f) {
        for (const glm::vec4& p : ktx.levels[0][std::size_t(f)].pixels)
            peakLevel0 = std::max({peakLevel0, p.r, p.g, p.b});
        for (const glm::vec4& p : ktx.levels[1][std::size_t(f)].pixels)
            peakLevel1 = std::max({peakLevel1, p.r, p.g, p.b});
    }
    // intensity = the brightest exported channel / 255^2.2: the residual's, far below the sun's pixels.
    const nlohmann::json gltf = readJson(out / "scene.gltf");
    const double exportedPeak =
        std::pow(255.0, 2.2) *
        gltf["extensions"]["EXT_lights_image_based"]["lights"][0]["intensity"].get<double>();
    EXPECT_LT(exportedPeak, 1e-2 * peakLevel0);
    EXPECT_GT(exportedPeak, 0.5 * peakLevel1);
    fs::remove_all(bake);
    fs::remove_all(out);
}

TEST(GltfExportErrors, BadBakeDirectoriesFailWithOneLineAndNoOutput) {
    const fs::path bake = ibl::test::makeBakeDir("gltf_bad");
    const fs::path out = ibl::test::freshTempDir("gltf_bad_out");
    const fs::path target = out / "scene.gltf";
    { std::ofstream(target) << "user's file\n"; }
    auto expectRefused = [&](const std::string& args, const std::string& mention) {
        CliRun r = runCli(args);
        EXPECT_EQ(r.exitCode, 1) << args;
        EXPECT_EQ(ibl::test::lineCount(r.err), 1) << r.err;
        EXPECT_NE(r.err.find(mention), std::string::npos) << r.err;
        EXPECT_EQ(ibl::test::entryCount(out), 1u) << "partial output after: " << args;
        std::ifstream in(target);
        EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "user's file\n");
    };
    expectRefused("gltf " + bake.string() + " -o " + (out / "scene.glb").string(), "scene.glb");
    {
        nlohmann::json diffuse = readJson(bake / "diffuse.json");
        diffuse["sh"]["irradiance"].erase(8);
        std::ofstream(bake / "diffuse.json") << diffuse.dump();
    }
    expectRefused("gltf " + bake.string() + " -o " + target.string(), "sh.irradiance needs 9 entries");
    fs::remove(bake / "diffuse.json");
    expectRefused("gltf " + bake.string() + " -o " + target.string(), "diffuse.json");
    fs::resize_file(bake / "specular.ktx2", 100);
    expectRefused("gltf " + bake.string() + " -o " + target.string(), "specular.ktx2");
    fs::remove_all(bake);
    fs::remove_all(out);
}
