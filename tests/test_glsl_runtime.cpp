// The runtime as GLSL (probe.glsl, baker/runtime/glsl/README.md) against the C++ runtime at the same points:
// a small scene bake with the sun extracted and a local box probe, its manifest loaded by the runtime, the
// points of four spheres shaded by shadeCpu here and by probe.glsl in WebGL2 (headless Chromium, SwiftShader:
// tests/js/glsl_runtime.mjs). Both read the same fp32 buffers (the set's bordered pyramids and DFG table),
// so the difference is fp32 arithmetic alone. Skipped, with the reason, without Node.js.
#include "cli_runner.h"
#include "scene_test_support.h"

#include <iblbake/runtime/runtime_manifest.h>

#include <cube.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <vector>

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

json vec3Json(const glm::vec3& v) {
    return {v.x, v.y, v.z};
}

// The structs as probe.glsl's uniforms: member names as in kernels/probe.h, arrays as arrays.
json chainJson(const ibl::LdChain& c) {
    return {{"shape", {{"baseFaceSize", c.shape.baseFaceSize}, {"levelCount", c.shape.levelCount}}},
            {"dataOffset", c.dataOffset},
            {"mapping", c.mapping}};
}

json volumeJson(const ibl::ProbeVolume& v) {
    return {{"shape", v.shape},           {"center", vec3Json(v.center)}, {"axisX", vec3Json(v.axisX)},
            {"axisY", vec3Json(v.axisY)}, {"axisZ", vec3Json(v.axisZ)},   {"extent", vec3Json(v.extent)}};
}

json paramsJson(const ibl::RuntimeParams& p) {
    return {{"flags", p.flags},
            {"dfgSize", p.dfgSize},
            {"localProbeCount", p.localProbeCount},
            {"pointCount", p.pointCount},
            {"distant", chainJson(p.distant)},
            {"sun",
             {{"direction", vec3Json(p.sun.direction)},
              {"angularRadius", p.sun.angularRadius},
              {"color", vec3Json(p.sun.color)},
              {"illuminance", p.sun.illuminance}}},
            {"dielectricF0", p.dielectricF0},
            {"sh", {{"c", std::vector<float>(std::begin(p.sh.c), std::end(p.sh.c))}}},
            {"irradiance", chainJson(p.irradiance)},
            {"distantRoughLayers",
             {{"faceSize", p.distantRoughLayers.faceSize},
              {"layerCount", p.distantRoughLayers.layerCount},
              {"dataOffset", p.distantRoughLayers.dataOffset}}}};
}

json localProbeJson(const ibl::LocalProbe& probe) {
    return {{"ld", chainJson(probe.ld)},
            {"proxy", volumeJson(probe.proxy)},
            {"influence", volumeJson(probe.influence)},
            {"captureOffset", vec3Json(probe.captureOffset)},
            {"fadeDistance", probe.fadeDistance},
            {"hasVisibility", probe.hasVisibility},
            {"visibilityOffset", probe.visibilityOffset}};
}

void writeFloats(const fs::path& file, const std::vector<float>& values) {
    std::ofstream(file, std::ios::binary)
        .write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * sizeof(float)));
}

std::vector<float> readFloats(const fs::path& file) {
    const std::string bytes = ibl::test::readBytes(file);
    std::vector<float> values(bytes.size() / sizeof(float));
    std::copy(bytes.begin(), bytes.begin() + std::ptrdiff_t(values.size() * sizeof(float)),
              reinterpret_cast<char*>(values.data()));
    return values;
}

// Four spheres of radius 0.5 seen along -z (orthographic, view +z), kSpherePixels across: inside the local
// probe's influence, in its fade band, outside it, and outside again with ao falling from 1 to 0 down the
// sphere. Perceptual roughness runs from 0 (left) to 1 (right) across each sphere; metal and dielectric
// alternate. Image pixel of every point, for the page's picture.
constexpr int kSpherePixels = 40;
struct SpherePoints {
    std::vector<ibl::ShadingPoint> points;
    std::vector<int> pixels; // y * width + x in a (4 kSpherePixels) x kSpherePixels image
};

SpherePoints spherePoints() {
    const glm::vec3 centres[4] = {
        {0.0f, 1.0f, 0.0f}, {2.6f, 1.0f, 0.0f}, {8.0f, 1.0f, 0.0f}, {8.0f, 1.0f, 2.0f}};
    const glm::vec3 colours[4] = {
        {0.95f, 0.64f, 0.54f}, {0.8f, 0.1f, 0.1f}, {0.91f, 0.92f, 0.92f}, {0.2f, 0.5f, 0.9f}};
    SpherePoints s;
    for (int k = 0; k < 4; ++k)
        for (int y = 0; y < kSpherePixels; ++y)
            for (int x = 0; x < kSpherePixels; ++x) {
                const float u = (float(x) + 0.5f) / kSpherePixels * 2.0f - 1.0f;
                const float v = 1.0f - (float(y) + 0.5f) / kSpherePixels * 2.0f;
                if (u * u + v * v >= 1.0f) continue;
                const glm::vec3 n(u, v, std::sqrt(1.0f - u * u - v * v));
                const float ao = k == 3 ? 0.5f * (v + 1.0f) : 1.0f;
                s.points.push_back(ibl::makeShadingPoint(centres[k] + 0.5f * n, n, {0.0f, 0.0f, 1.0f},
                                                         colours[k], k % 2 == 0 ? 1.0f : 0.0f,
                                                         0.5f * (u + 1.0f), ao));
                s.pixels.push_back(y * 4 * kSpherePixels + k * kSpherePixels + x);
            }
    return s;
}

float median(std::vector<float> v) {
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
    return v[v.size() / 2];
}

// |a - b| over the larger channel of b (the C++ result), per point; the floor keeps black points (a metal's
// diffuse, the distant points' local alpha) from dividing by zero.
float relativeDifference(const glm::vec3& glsl, const glm::vec3& cpp, float floor) {
    const glm::vec3 d = glm::abs(glsl - cpp);
    return std::max({d.x, d.y, d.z}) / std::max({std::abs(cpp.x), std::abs(cpp.y), std::abs(cpp.z), floor});
}

// The scene (dir/scene.json): the park, its sun extracted, one box probe rotated 30 degrees; small faces,
// KTX2 in `format`. Returns the bake's output directory.
fs::path bakeScene(const fs::path& dir, const std::string& format) {
    const json box = {{"shape", "box"}, {"center", {0, 1, 0}}, {"rotation", {0, 30, 0}}};
    json proxy = box, influence = box;
    proxy["halfExtents"] = {4, 2, 4};
    influence["halfExtents"] = {3, 1.5, 3};
    const json scene = {{"environment",
                         {{"file", ibl::test::kSampleHdri},
                          {"calibration", {{"sunIlluminance", 100000}}},
                          {"extractSun", true}}},
                        {"probes", json::array({{{"name", "room"},
                                                 {"capture", ibl::test::kSampleHdri},
                                                 {"position", {0.5, 1, 0}},
                                                 {"proxy", proxy},
                                                 {"influence", influence},
                                                 {"fadeDistance", 1.0}}})},
                        {"materials", {{"diffuseModel", "disney"}}},
                        {"outputs",
                         {{"directory", "out"},
                          {"ktx2Format", format},
                          {"quality", "draft"},
                          {"faceSize", 64},
                          {"probeFaceSize", 32},
                          {"dfgSize", 32},
                          {"irradianceCube", true},
                          {"irradianceFaceSize", 16}}}};
    const fs::path file = dir / "scene.json";
    ibl::test::writeText(file, scene.dump(2));
    const ibl::test::CliRun bake = ibl::test::runCli("bake " + file.string() + " --quiet");
    EXPECT_EQ(bake.exitCode, 0) << bake.err;
    return dir / "out";
}

// Writes what the page uploads into `dir`: one float array (distant LD + irradiance cube, DFG, local LD) for
// iblData, the points, the C++ results (for its picture), the uniforms.
void writePageInput(const fs::path& dir, const ibl::ProbeSet& set, const ibl::RuntimeOptions& options,
                    const SpherePoints& spheres, const std::vector<ibl::ShadeResult>& cpp) {
    std::vector<float> data = set.distantData();
    const std::size_t dfgOffset = data.size();
    data.insert(data.end(), set.dfg().data.begin(), set.dfg().data.end());
    const std::size_t localOffset = data.size();
    data.insert(data.end(), set.localLdData().begin(), set.localLdData().end());
    writeFloats(dir / "data.f32", data);
    std::vector<float> points, cppOut;
    for (std::size_t i = 0; i < spheres.points.size(); ++i) {
        const ibl::ShadingPoint& p = spheres.points[i];
        points.insert(points.end(), {p.position.x, p.position.y, p.position.z, p.metallic, p.normal.x,
                                     p.normal.y, p.normal.z, p.perceptualRoughness, p.view.x, p.view.y,
                                     p.view.z, p.ao, p.baseColor.x, p.baseColor.y, p.baseColor.z, 0.0f});
        const ibl::ShadeResult& r = cpp[i];
        cppOut.insert(cppOut.end(), {r.diffuse.x, r.diffuse.y, r.diffuse.z, r.localAlpha, r.specular.x,
                                     r.specular.y, r.specular.z, 0.0f});
    }
    writeFloats(dir / "points.f32", points);
    writeFloats(dir / "cpp.f32", cppOut);
    json probes = json::array();
    for (const ibl::LocalProbe& probe : set.localProbes())
        probes.push_back(localProbeJson(probe));
    const json input = {
        {"params", paramsJson(ibl::makeRuntimeParams(set, options, spheres.points.size()))},
        {"localProbes", probes},
        {"uniforms",
         {{"iblDistantLdOffset", 0}, {"iblDfgOffset", dfgOffset}, {"iblLocalLdOffset", localOffset}}},
        {"pointCount", spheres.points.size()},
        {"image", {{"width", 4 * kSpherePixels}, {"height", kSpherePixels}, {"pixels", spheres.pixels}}}};
    ibl::test::writeText(dir / "input.json", input.dump());
}

// tests/js/glsl_runtime.mjs on `dir`: exit code and output.
std::pair<int, std::string> runPage(const fs::path& dir) {
    const std::string command = std::string(IBLBAKE_NODE) + " " + IBLBAKE_JS_DIR + "/glsl_runtime.mjs " +
                                IBLBAKE_GLSL_FILE + " " + dir.string() + " 2>&1";
    FILE* pipe = ::popen(command.c_str(), "r");
    std::string out;
    char buffer[4096];
    while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe))
        out.append(buffer, n);
    return {::pclose(pipe), out};
}

class GlslRuntime : public ::testing::Test {
  protected:
    void SetUp() override {
        if (std::string(IBLBAKE_NODE).empty())
            GTEST_SKIP()
                << "Node.js was not found when CMake configured the build (.ci/install-deps installs it)";
        ASSERT_TRUE(fs::exists(fs::path(IBLBAKE_JS_DIR) / "node_modules" / "puppeteer-core"))
            << IBLBAKE_JS_DIR << ": npm ci has not run (the CTest fixture js_npm_ci installs the packages)";
    }

    // The spheres shaded by the C++ runtime and by probe.glsl in WebGL2 (results and picture in
    // dir), compared: at most 1e-3 relative to the point's radiance.
    static void expectAgreement(const fs::path& dir, const ibl::ProbeSet& set,
                                const ibl::RuntimeOptions& options) {
        const std::string name = dir.filename().string();
        const SpherePoints spheres = spherePoints();
        const std::vector<ibl::ShadeResult> cpp = ibl::shadeCpu(set, spheres.points, options);
        writePageInput(dir, set, options, spheres, cpp);
        const auto [exitCode, out] = runPage(dir);
        ASSERT_EQ(exitCode, 0) << out;
        std::printf("%s", out.c_str());

        const std::vector<float> glsl = readFloats(dir / "glsl.f32");
        ASSERT_EQ(glsl.size(), 8 * cpp.size());
        // The terms relative to the point's total radiance (a term small beside the other may differ more
        // in its own terms without it showing), the total to itself; alpha absolute.
        std::vector<float> total, diffuse, specular, alpha;
        for (std::size_t i = 0; i < cpp.size(); ++i) {
            const float* g = &glsl[8 * i];
            const glm::vec3 gd(g[0], g[1], g[2]), gs(g[4], g[5], g[6]);
            const glm::vec3 sum = cpp[i].diffuse + cpp[i].specular;
            const float scale = std::max({sum.x, sum.y, sum.z, 1e-6f});
            total.push_back(relativeDifference(gd + gs, sum, 1e-6f));
            diffuse.push_back(relativeDifference(gd, cpp[i].diffuse, scale));
            specular.push_back(relativeDifference(gs, cpp[i].specular, scale));
            alpha.push_back(std::abs(g[3] - cpp[i].localAlpha));
        }
        const auto report = [&](const char* what, const std::vector<float>& v) {
            std::printf("%s: GLSL vs C++ %-8s max %.3g median %.3g over %zu points\n", name.c_str(), what,
                        *std::max_element(v.begin(), v.end()), median(v), v.size());
            return *std::max_element(v.begin(), v.end());
        };
        EXPECT_LE(report("total", total), 1e-3f);
        EXPECT_LE(report("diffuse", diffuse), 1e-3f);
        EXPECT_LE(report("specular", specular), 1e-3f);
        EXPECT_LE(report("alpha", alpha), 1e-3f);
        std::printf("%s: picture (rows GLSL, C++, |difference| x 1000): %s\n", name.c_str(),
                    (dir / "glsl_runtime.png").string().c_str());
    }

    // A fresh directory per test (CTest runs them in parallel), in the build tree: the artifacts stay.
    static fs::path testDir(const std::string& name) {
        const fs::path dir = fs::path(IBLBAKE_GLSL_RUNTIME_DIR) / name;
        fs::remove_all(dir);
        fs::create_directories(dir);
        return dir;
    }
};

} // namespace

// The default format and what the manifest's materials ask for: irradiance cube, Disney diffuse, the sun's
// disk quadrature, dominant direction, occlusions, distance-based roughness.
TEST_F(GlslRuntime, ManifestOptionsAgreeWithTheCppRuntime) {
    const fs::path dir = testDir("manifest_options");
    ibl::ManifestProbeSet loaded = ibl::loadProbeSetFromManifest(bakeScene(dir, "rgba16f"));
    ASSERT_TRUE(loaded.set.sun().has_value());
    ASSERT_EQ(loaded.set.localProbes().size(), 1u);
    ASSERT_FALSE(
        loaded.options.specularTaps);   // materials.specularLookup's default, as the manifest records it
    loaded.options.specularTaps = true; // the selectable taps: GLSL must read what C++ reads
    ASSERT_TRUE(loaded.set.hasIrradianceCube());
    // Rough layers after the irradiance cube in the distant buffer (what GLSL must read is the C++ read,
    // so any smooth data does): the spheres' roughness 0-1 crosses the chain, the blend and the layers.
    const std::uint32_t n = ibl::roughLayerFaceSize(loaded.set.distantLd().layout.baseFaceSize);
    std::vector<ibl::CubeMap> layers;
    for (std::uint32_t k = 0; k < IBL_ROUGH_LAYER_COUNT; ++k) {
        ibl::CubeMap layer{int(n)};
        for (int f = 0; f < 6; ++f)
            for (std::uint32_t y = 0; y < n; ++y)
                for (std::uint32_t x = 0; x < n; ++x) {
                    const glm::vec3 d = ibl::cubeTexelDirection(f, x, y, n);
                    layer.faces[f].at(int(x), int(y)) =
                        glm::vec4(1.0f + d.x, 1.0f + d.y, 0.5f * float(k), 1.0f);
                }
        layers.push_back(std::move(layer));
    }
    loaded.set.setRoughLayers(layers);
    expectAgreement(dir, loaded.set, loaded.options);
}

// The other branches: L2 SH diffuse, Lambert, Listing 23's diffuse direction, f90 from f0, Listing 6's
// normalized representative point for the sun, no energy compensation, the split sum's single LD read (the
// manifest's options read the fitted taps).
TEST_F(GlslRuntime, OtherOptionsAgreeWithTheCppRuntime) {
    const fs::path dir = testDir("other_options");
    const ibl::ManifestProbeSet loaded = ibl::loadProbeSetFromManifest(bakeScene(dir, "rgba16f"));
    ibl::RuntimeOptions options = loaded.options;
    options.irradianceCube = false;
    options.diffuseModel = ibl::DiffuseModel::Lambert;
    options.diffuseDominantDirection = true;
    options.f90FromF0 = true;
    options.sunQuadrature = false;
    options.energyCompensation = false;
    options.specularTaps = false;
    expectAgreement(dir, loaded.set, options);
}

// rgba32f keeps the sun's pixels in level 0 (IBL_RT_SUN_IN_LEVEL0): mirror points see texels ~1e9.
TEST_F(GlslRuntime, SunInLevel0AgreesWithTheCppRuntime) {
    const fs::path dir = testDir("sun_in_level0");
    const ibl::ManifestProbeSet loaded = ibl::loadProbeSetFromManifest(bakeScene(dir, "rgba32f"));
    ASSERT_TRUE(loaded.set.distantLd().sunInLevel0);
    expectAgreement(dir, loaded.set, loaded.options);
}

// A local probe with a texel visibility (4.9.1.2) in front of the bake's probe: a window band of visibility
// 0 fading to 1, colour premultiplied, every level; evaluated first (smaller influence), so the composition
// hands parts of the lobes on to the room probe and the distant one.
TEST_F(GlslRuntime, LocalVisibilityAgreesWithTheCppRuntime) {
    const fs::path dir = testDir("local_visibility");
    const ibl::ManifestProbeSet loaded = ibl::loadProbeSetFromManifest(bakeScene(dir, "rgba16f"));
    ibl::ProbeSet set = loaded.set;
    ibl::CubeMapChain chain;
    for (int n = 32; n >= 1; n /= 2) {
        ibl::CubeMap level(n);
        for (int f = 0; f < 6; ++f)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    const glm::vec3 d = glm::normalize(glm::vec3(ibl::cubeFaceDirection(
                        f, (float(x) + 0.5f) / float(n), (float(y) + 0.5f) / float(n))));
                    const float visibility = std::clamp(0.5f + 2.0f * d.x, 0.0f, 1.0f);
                    level.faces[f].at(x, y) = glm::vec4((0.5f + 0.5f * d) * visibility, visibility);
                }
        chain.levels.push_back(level);
    }
    ibl::LocalProbeDesc desc;
    desc.proxy = ibl::boxVolume(glm::vec3(1, 1, 0), glm::vec3(2.5f, 1.5f, 2.5f));
    desc.fadeDistance = 0.5f;
    ASSERT_EQ(set.addLocalProbe(desc, ibl::ldPyramidFromChain(chain, ibl::MipMapping::Frostbite,
                                                              ibl::ChainAlpha::PremultipliedVisibility)),
              0u);
    ASSERT_EQ(set.localProbes()[0].hasVisibility, 1u);
    expectAgreement(dir, set, loaded.options);
}
