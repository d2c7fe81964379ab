// A local probe's visibility through the whole chain (issue 16): a capture whose alpha is the visibility
// (an RGBA EXR) is ingested with it (IngestSettings::readAlpha: read, repaired, resampled with colour's
// exact-area weights), baked by the scene's probe-ld stage with bakeSpecularWithVisibility, written with the
// KTX2 key iblbake.visibility and recorded in the manifest, and loaded by loadProbeSetFromManifest into a
// LocalProbe with a visibility that the runtime composes with the distant probe (Frostbite 2014 4.9.5).
#include "cli_runner.h"
#include "room_test_support.h"
#include "scene_test_support.h"

#include <iblbake/baker/bake_scene.h>
#include <iblbake/baker/ingest.h>
#include <iblbake/ktx2/ktx2.h>
#include <iblbake/runtime/runtime_manifest.h>
#include <iblbake/scene/scene.h>
#include <iblbake/scene/scene_plan.h>

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>
#include <nlohmann/json.hpp>

#include <cube.h>
#include <glm/gtc/type_ptr.hpp>

#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <random>

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using namespace ibl;
using namespace rt_test;
using namespace ibl::test;

const ProbeVolume& kRoom = kWindowRoom;
const glm::vec3& kCapturePoint = kWindowRoomCapturePoint;
constexpr int kProbeFaceSize = 64;

// The distant map: a smooth sky (no sun, so that a 64-px cube holds it to well under 1%).
glm::vec3 outside(glm::vec3 d) {
    return glm::vec3(0.3f, 0.5f, 1.0f) * (0.6f + 0.4f * std::max(d.y, 0.0f)) + glm::vec3(0.2f * d.z + 0.2f);
}

// docs/conventions.md lat-long mapping, pixel centres: u = 0.5 - longitude / (2 pi), v = 0.5 - latitude / pi.
glm::vec3 latLongDirection(double u, double v) {
    const double lon = (0.5 - u) * 2.0 * std::numbers::pi, lat = (0.5 - v) * std::numbers::pi;
    return glm::vec3(std::cos(lat) * std::sin(lon), std::sin(lat), std::cos(lat) * std::cos(lon));
}

// A W x H lat-long EXR of `channels` (3 or 4) whose pixel is the mean of 4 x 4 sub-pixel values of `f`.
void writeLatLongExr(const fs::path& file, int w, int h, int channels,
                     const std::function<glm::vec4(glm::vec3)>& f) {
    std::vector<float> pixels(std::size_t(w) * h * channels);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            glm::vec4 sum(0.0f);
            for (int j = 0; j < 4; ++j)
                for (int i = 0; i < 4; ++i)
                    sum += f(latLongDirection((x + (i + 0.5) / 4) / w, (y + (j + 0.5) / 4) / h));
            for (int c = 0; c < channels; ++c)
                pixels[(std::size_t(y) * w + x) * channels + c] = sum[c] / 16.0f;
        }
    auto out = OIIO::ImageOutput::create(file.string());
    ASSERT_TRUE(out);
    ASSERT_TRUE(out->open(file.string(), OIIO::ImageSpec(w, h, channels, OIIO::TypeDesc::FLOAT)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    out->close();
}

// The room seen from the capture point, premultiplied: a wall's colour with alpha 1; the window RGBA 0
// (visibility), or with frozenSky the outside with alpha 1 (what a capture without visibility holds).
glm::vec4 roomCapture(glm::vec3 d, bool frozenSky) {
    const glm::vec3 hit = analyticHitLocal(kRoom, kCapturePoint, d);
    if (!inWindow(hit)) return glm::vec4(kWallColors[wallOf(kRoom, hit)], 1.0f);
    return frozenSky ? glm::vec4(outside(d), 1.0f) : glm::vec4(0.0f);
}

// A scene directory: env.exr (the outside), the probe "room" at the capture point with capture room.exr
// (written by the caller), and small fast outputs.
struct SceneDir {
    fs::path dir;
    json scene;
    explicit SceneDir(const std::string& name) : dir(freshTempDir(name)) {
        writeLatLongExr(dir / "env.exr", 256, 128, 3,
                        [](glm::vec3 d) { return glm::vec4(outside(d), 1.0f); });
        scene = {
            {"environment", {{"file", "env.exr"}}},
            {"probes",
             json::array(
                 {{{"name", "room"},
                   {"capture", "room.exr"},
                   {"position", {kCapturePoint.x, kCapturePoint.y, kCapturePoint.z}},
                   {"proxy", {{"shape", "box"}, {"center", {0, 1.5, 0}}, {"halfExtents", {3, 1.5, 3}}}}}})},
            {"outputs",
             {{"directory", "out"},
              {"quality", "draft"},
              {"faceSize", 64},
              {"probeFaceSize", kProbeFaceSize},
              {"dfgSize", 32}}}};
    }
    ~SceneDir() { fs::remove_all(dir); }
    fs::path capture() const { return dir / "room.exr"; }
    fs::path out() const { return dir / "out"; }
    BakeSummary bake(Backend backend = Backend::Cpu) const {
        writeText(dir / "scene.json", scene.dump(2));
        BakeOptions options;
        options.backend = backend;
        ProgressSink silent;
        return bakeScene(loadSceneFile(dir / "scene.json"), options, silent);
    }
    json probeEntry() const {
        return json::parse(readBytes(out() / "manifest.json"))["products"]["probes"].at(0);
    }
};

// Bakes the scene, loads it through the manifest and shades mirror points: those whose lookups see only the
// window get the distant map, those that see one wall that wall.
void expectMirrorsThroughTheWindow(const SceneDir& d) {
    const BakeSummary summary = d.bake();
    ASSERT_TRUE(summary.ok) << summary.error;
    const json probe = d.probeEntry();
    ASSERT_TRUE(probe.contains("visibility"));
    EXPECT_EQ(probe["visibility"]["convention"], "premultiplied-alpha");
    EXPECT_EQ(probe["visibility"]["channel"], "A");
    EXPECT_FALSE(probe.contains("alphaRepaired"));
    const Ktx2Image stored = readKtx2(d.out() / "probe_room.ktx2");
    EXPECT_EQ(stored.keyValues.at("iblbake.visibility"), "premultiplied-alpha");
    EXPECT_EQ(stored.alpha, Ktx2Alpha::Premultiplied) << "the DFD's KHR_DF_FLAG_ALPHA_PREMULTIPLIED";

    const ManifestProbeSet loaded = loadProbeSetFromManifest(d.out());
    ASSERT_EQ(loaded.set.localProbes().size(), 1u);
    EXPECT_EQ(loaded.set.localProbes()[0].hasVisibility, 1u);

    const RoomMirrors m = checkRoomMirrors(
        loaded.set, loaded.options, windowRoomMirrorPoints(4000, 16, kProbeFaceSize),
        [&](const ShadingPoint&, glm::vec3 R) { return outside(R); }, "scene room");
    EXPECT_GT(m.throughWindow, 200);
    EXPECT_GT(m.onWall, 1500);
}

TEST(SceneVisibility, MirrorsThroughTheWindowGetTheDistantMapAndTheOthersTheWall) {
    SceneDir d("scene_visibility_room");
    writeLatLongExr(d.capture(), 512, 256, 4, [](glm::vec3 v) { return roomCapture(v, false); });
    expectMirrorsThroughTheWindow(d);
}

// The same room with the visibility as a separate mask (probes[].visibilityMask, a one-channel image) and a
// capture whose window holds the frozen sky: the mask replaces it by the distant probe's radiance.
TEST(SceneVisibility, AVisibilityMaskImageDoesWhatTheCapturesAlphaDoes) {
    SceneDir d("scene_visibility_mask");
    writeLatLongExr(d.capture(), 512, 256, 3, [](glm::vec3 v) { return roomCapture(v, true); });
    writeLatLongExr(d.dir / "mask.exr", 512, 256, 1,
                    [](glm::vec3 v) { return glm::vec4(roomCapture(v, false).w); });
    d.scene["probes"][0]["visibilityMask"] = "mask.exr";
    expectMirrorsThroughTheWindow(d);
    // A mask of another size is refused naming the mask.
    writeLatLongExr(d.dir / "mask.exr", 256, 128, 1, [](glm::vec3) { return glm::vec4(1.0f); });
    const BakeSummary refused = d.bake();
    EXPECT_FALSE(refused.ok);
    EXPECT_NE(refused.error.find("mask.exr: the visibility mask is 256x128, but "), std::string::npos)
        << refused.error;
    EXPECT_NE(refused.error.find("room.exr is 512x256"), std::string::npos) << refused.error;
}

// The probe-ld stage on OpenCL and on the CPU: the colour x visibility and the visibility of every level
// agree.
TEST(SceneVisibility, OpenClAndCpuBakesAgree) {
    std::vector<LdPyramid> pyramids;
    for (Backend backend : {Backend::OpenCL, Backend::Cpu}) {
        SceneDir d(std::string("scene_visibility_backend_") + (backend == Backend::Cpu ? "cpu" : "opencl"));
        writeLatLongExr(d.capture(), 256, 128, 4, [](glm::vec3 v) { return roomCapture(v, false); });
        const BakeSummary summary = d.bake(backend);
        ASSERT_TRUE(summary.ok) << summary.error;
        if (backend == Backend::OpenCL && summary.backend != "opencl") GTEST_SKIP() << "no OpenCL device";
        pyramids.push_back(loadLdKtx2(d.out() / "probe_room.ktx2"));
    }
    const LdPyramid &cl = pyramids[0], &cpu = pyramids[1];
    ASSERT_EQ(cl.data.size(), cpu.data.size());
    ASSERT_EQ(cl.visibility.size(), cpu.visibility.size());
    ASSERT_FALSE(cpu.visibility.empty());
    double colour = 0.0, visibility = 0.0;
    for (std::size_t i = 0; i < cpu.data.size(); ++i)
        colour = std::max(colour, double(std::abs(cl.data[i] - cpu.data[i])));
    for (std::size_t i = 0; i < cpu.visibility.size(); ++i)
        visibility = std::max(visibility, double(std::abs(cl.visibility[i] - cpu.visibility[i])));
    std::printf("scene probe, OpenCL vs CPU: colour x visibility %.2g, visibility %.2g (max abs)\n", colour,
                visibility);
    EXPECT_LT(colour, 2e-3); // fp16 storage: a wall colour near 1 rounds at 5e-4
    EXPECT_LT(visibility, 2e-3);
}

// A capture whose alpha is 1 everywhere bakes the bytes of the same capture without alpha, and the manifest
// records no visibility (as before visibility existed).
TEST(SceneVisibility, AlphaOneEverywhereBakesTheBytesOfNoAlpha) {
    std::string bytes[2];
    for (int channels : {3, 4}) {
        SceneDir d("scene_visibility_alpha_one_" + std::to_string(channels));
        writeLatLongExr(d.capture(), 256, 128, channels, [](glm::vec3 v) { return roomCapture(v, true); });
        const BakeSummary summary = d.bake();
        ASSERT_TRUE(summary.ok) << summary.error;
        EXPECT_FALSE(d.probeEntry().contains("visibility"));
        EXPECT_FALSE(d.probeEntry().contains("alphaRepaired"));
        bytes[channels - 3] = readBytes(d.out() / "probe_room.ktx2");
        EXPECT_EQ(readKtx2(d.out() / "probe_room.ktx2").keyValues.count("iblbake.visibility"), 0u);
    }
    ASSERT_FALSE(bytes[0].empty());
    EXPECT_TRUE(bytes[0] == bytes[1]) << "the probe's KTX2 differs between RGB and RGBA (alpha 1) captures";
}

// Alpha 0 everywhere: the probe is transparent at every level, every point gets the distant probe alone.
TEST(SceneVisibility, AlphaZeroEverywhereIsTransparent) {
    SceneDir d("scene_visibility_alpha_zero");
    writeLatLongExr(d.capture(), 256, 128, 4, [](glm::vec3) { return glm::vec4(0.0f); });
    const BakeSummary summary = d.bake();
    ASSERT_TRUE(summary.ok) << summary.error;
    ASSERT_TRUE(d.probeEntry().contains("visibility"));
    const ManifestProbeSet loaded = loadProbeSetFromManifest(d.out());
    std::vector<ShadingPoint> points;
    for (int i = 0; i < 64; ++i) {
        const float t = float(i) / 63.0f;
        const glm::vec3 n = glm::normalize(glm::vec3(std::cos(7.0f * t), 0.8f - t, std::sin(7.0f * t)));
        points.push_back(makeShadingPoint(glm::vec3(-2.0f + 4.0f * t, 1.0f, 0.5f), n,
                                          glm::normalize(n + glm::vec3(0.3f, 0.5f, 0.2f)), glm::vec3(0.7f),
                                          float(i % 2), t));
    }
    ProbeSet distantOnly(loadLdKtx2(d.out() / "specular.ktx2"), loadDfgKtx2(d.out() / "dfg_lut.ktx2"),
                         ShCoefficients{});
    distantOnly.setRoughLayers(loadRoughLayersKtx2(d.out() / kRoughLayersFile));
    RuntimeOptions options = loaded.options;
    options.diffuse = false;
    const std::vector<glm::vec4> a = evaluateCpu(loaded.set, points, options);
    const std::vector<glm::vec4> b = evaluateCpu(distantOnly, points, options);
    for (std::size_t i = 0; i < points.size(); ++i) {
        EXPECT_EQ(a[i].w, 0.0f) << i;
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(a[i][c], b[i][c], 1e-6f * std::max(1.0f, b[i][c])) << i << " " << c;
    }
}

// Hard case: alpha NaN, negative and over 1 (+Inf included) in the file are repaired (NaN and negative: the
// pixel transparent; over 1: 1), counted in the manifest and the bake report, and the bake is finite.
TEST(SceneVisibility, AlphaNanNegativeAndOverOneAreRepairedAndCounted) {
    SceneDir d("scene_visibility_alpha_repair");
    const int w = 128, h = 64;
    std::vector<float> pixels(std::size_t(w) * h * 4);
    std::uint64_t nan = 0, negative = 0, overOne = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float* p = &pixels[(std::size_t(y) * w + x) * 4];
            const glm::vec4 v = roomCapture(latLongDirection((x + 0.5) / w, (y + 0.5) / h), false);
            for (int c = 0; c < 4; ++c)
                p[c] = v[c];
            switch ((x * 7 + y * 3) % 29) {
            case 0:
                p[3] = std::numeric_limits<float>::quiet_NaN(), ++nan;
                break;
            case 1:
                p[3] = -0.5f, ++negative;
                break;
            case 2:
                p[3] = -std::numeric_limits<float>::infinity(), ++negative;
                break;
            case 3:
                p[3] = 2.0f, ++overOne;
                break;
            case 4:
                p[3] = std::numeric_limits<float>::infinity(), ++overOne;
                break;
            default:
                break;
            }
        }
    {
        auto out = OIIO::ImageOutput::create(d.capture().string());
        ASSERT_TRUE(out);
        ASSERT_TRUE(out->open(d.capture().string(), OIIO::ImageSpec(w, h, 4, OIIO::TypeDesc::FLOAT)));
        ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
        out->close();
    }
    const BakeSummary summary = d.bake();
    ASSERT_TRUE(summary.ok) << summary.error;
    const json probe = d.probeEntry();
    ASSERT_TRUE(probe.contains("visibility"));
    ASSERT_TRUE(probe.contains("alphaRepaired"));
    EXPECT_EQ(probe["alphaRepaired"]["nan"].get<std::uint64_t>(), nan);
    EXPECT_EQ(probe["alphaRepaired"]["negative"].get<std::uint64_t>(), negative);
    EXPECT_EQ(probe["alphaRepaired"]["overOne"].get<std::uint64_t>(), overOne);
    const std::string line = "alpha repaired: " + std::to_string(nan) + " NaN, " + std::to_string(negative) +
                             " negative, " + std::to_string(overOne) + " over 1";
    bool reported = false;
    for (const ProductReport& r : summary.report)
        reported = reported || (r.name == "probe:room" && r.description.find(line) != std::string::npos);
    EXPECT_TRUE(reported) << "the bake report names the repairs: " << line;

    const ManifestProbeSet loaded = loadProbeSetFromManifest(d.out());
    ASSERT_EQ(loaded.set.localProbes()[0].hasVisibility, 1u);
    std::vector<ShadingPoint> points;
    for (int i = 0; i < 256; ++i) {
        const float t = float(i) / 255.0f;
        const glm::vec3 n = glm::normalize(glm::vec3(std::cos(11.0f * t), 0.7f - t, std::sin(11.0f * t)));
        points.push_back(makeShadingPoint(glm::vec3(-2.5f + 5.0f * t, 1.5f, 0.2f), n,
                                          glm::normalize(n + glm::vec3(0.2f, 0.4f, -0.3f)), glm::vec3(0.5f),
                                          float(i % 2), float(i % 5) / 4.0f));
    }
    for (const glm::vec4& v : evaluateCpu(loaded.set, points, loaded.options))
        for (int c = 0; c < 4; ++c)
            ASSERT_TRUE(std::isfinite(v[c]));
}

// The ingest alone: colour x alpha and alpha keep their solid-angle means through the lat-long -> cube
// resampling (the same exact-area weights), and alpha stays in [0, 1].
TEST(IngestAlpha, ResamplingKeepsTheMeansOfColourTimesAlphaAndAlpha) {
    const fs::path dir = freshTempDir("ingest_alpha");
    const fs::path file = dir / "capture.exr";
    // A soft-edged alpha (a curtain of 0.3-0.9 and the window at 0) on the room's colours.
    auto capture = [](glm::vec3 v) {
        glm::vec4 c = roomCapture(v, false);
        if (v.z > 0.5f && c.w > 0.0f) c *= 0.3f + 0.6f * std::abs(v.y);
        return c;
    };
    writeLatLongExr(file, 256, 128, 4, capture);
    IngestSettings settings;
    settings.readAlpha = true;
    settings.sourceFaceSize = 32;
    const SourceEnvironment env = ingestEnvironment({file}, settings);
    ASSERT_TRUE(env.report.hasAlpha);
    // Means over the sphere of the file (pixel rows weighted by their solid angle) and of the cube.
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(file.string());
    ASSERT_TRUE(in);
    const int w = in->spec().width, h = in->spec().height;
    std::vector<float> pixels(std::size_t(w) * h * 4);
    ASSERT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, pixels.data()));
    glm::dvec4 fileMean(0.0), cubeMean(0.0);
    for (int y = 0; y < h; ++y) {
        const double omega = std::cos(std::numbers::pi * y / h) - std::cos(std::numbers::pi * (y + 1) / h);
        for (int x = 0; x < w; ++x)
            fileMean += omega / (2.0 * w) * glm::dvec4(glm::make_vec4(&pixels[(std::size_t(y) * w + x) * 4]));
    }
    const int n = env.cube.faceSize;
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const glm::vec4 t = env.cube.faces[f].at(x, y);
                EXPECT_TRUE(t.w >= 0.0f && t.w <= 1.0f);
                cubeMean += double(cubeTexelSolidAngle(x, y, n)) / (4.0 * std::numbers::pi) * glm::dvec4(t);
            }
    for (int c = 0; c < 4; ++c)
        EXPECT_NEAR(cubeMean[c], fileMean[c], 1e-4 * fileMean[c]) << "channel " << c;
    std::printf("ingest alpha: mean RGB x A %.6f %.6f %.6f, A %.6f (file) -> %.6f %.6f %.6f, %.6f (cube)\n",
                fileMean.r, fileMean.g, fileMean.b, fileMean.a, cubeMean.r, cubeMean.g, cubeMean.b,
                cubeMean.a);
    fs::remove_all(dir);
}

} // namespace
