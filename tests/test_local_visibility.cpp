// Local probes with a texel visibility (Frostbite 2014 4.9.1.2) composed by the 4.9.5 pseudo-code:
// nested probes with partial visibility against the pseudo-code transcribed, its order dependence and the
// same-lobe rule of the notes' erratum, a room whose window is transparent (the distant probe shows
// through it, the walls stay), probes without visibility unchanged to the bit, and the hard cases
// (visibility 0 everywhere, NaN, negative, above 1).
#include "room_test_support.h"
#include "runtime_test_support.h"

#include <iblbake/core/error.h>
#include <iblbake/ktx2/ktx2.h>

#include <filesystem>
#include <unistd.h>

#include <cstring>
#include <limits>
#include <random>

namespace {

using namespace ibl;
using namespace rt_test;

// One level of 4x4 faces holding colour x visibility and the visibility (what an alpha bake writes).
LdPyramid premultipliedConstant(glm::vec3 colour, float visibility) {
    CubeMap cube(4);
    for (ImageRGBA& face : cube.faces)
        for (glm::vec4& texel : face.pixels)
            texel = glm::vec4(colour * visibility, visibility);
    return ldPyramidFromChain(CubeMapChain{{cube}}, MipMapping::Frostbite,
                              ChainAlpha::PremultipliedVisibility);
}

LdPyramid constantLd(glm::vec3 colour) {
    return ldPyramidFromChain(CubeMapChain{{makeCube(4, [&](glm::vec3) { return colour; })}});
}

struct Layer {
    LocalProbeDesc desc;
    glm::vec3 colour;
    float visibility;
};

// The notes' pseudo-code (4.9.5, medium and large range, SSR alpha 0), transcribed: the probes in the
// order given, localLightProbe.rgb = the colour, localLightProbe.a = influence weight x visibility.
glm::vec4 pseudoCode(const std::vector<Layer>& layers, glm::vec3 distant, glm::vec3 position) {
    glm::vec3 rgb(0.0f);
    float alpha = 0.0f;
    for (std::size_t i = 0; i < layers.size() && alpha < 1.0f; ++i) {
        float localAlpha = influenceWeight(layers[i].desc.proxy, layers[i].desc.fadeDistance, position) *
                           layers[i].visibility;
        float a = std::clamp(localAlpha - alpha, 0.0f, 1.0f);
        rgb += layers[i].colour * a;
        alpha = std::clamp(a + alpha, 0.0f, 1.0f);
    }
    if (alpha < 1.0f) rgb += distant * (1.0f - alpha);
    return glm::vec4(rgb, alpha);
}

ProbeSet setOf(const std::vector<Layer>& layers, glm::vec3 distant) {
    ProbeSet set(constantLd(distant), dfgTableFromImage(dfgLut()), ShCoefficients{});
    for (const Layer& layer : layers)
        set.addLocalProbe(layer.desc, premultipliedConstant(layer.colour, layer.visibility));
    return set;
}

// The composed LD (kernels/probe.h composeSpecularLd) of a mirror at `position` looking along +Z.
glm::vec4 composedMirrorLd(const ProbeSet& set, glm::vec3 position) {
    RuntimeParams params = makeRuntimeParams(set, RuntimeOptions{}, 1);
    ProbeSample s = composeSpecularLd(params, set.distantData().data(), set.localProbes().data(),
                                      set.localLdData().data(), position, glm::vec3(0, 0, 1),
                                      glm::vec3(0, 0, 1), glm::vec3(0, 0, 1), 1.0f, 0.0f);
    return glm::vec4(glm::vec3(s.radiance), s.alpha);
}

// Mirror points on the Z axis looking along +Z: every proxy centred on the axis is hit straight ahead, so the
// lookup is a face centre, where the bilinear weights are 1/4 and constant dyadic texels read back exactly;
// the influence weights vary through the fades.
std::vector<glm::vec3> axisPoints() {
    std::vector<glm::vec3> points;
    for (float z = -3.5f; z <= 3.5f; z += 0.03125f)
        points.push_back(glm::vec3(0.0f, 0.0f, z));
    return points;
}

std::vector<ShadingPoint> mirrorPoints(const std::vector<glm::vec3>& positions) {
    std::vector<ShadingPoint> points;
    for (glm::vec3 p : positions)
        points.push_back(
            makeShadingPoint(p, glm::vec3(0, 0, 1), glm::vec3(0, 0, 1), glm::vec3(1), 1.0f, 0.0f));
    return points;
}

TEST(VisibilityComposition, NestedProbesWithPartialVisibilityAreThePseudoCodeExactly) {
    const glm::vec3 red(1, 0, 0), green(0, 1, 0), blue(0, 0, 1);
    Layer small{{}, red, 0.5f}, big{{}, green, 0.75f};
    small.desc.proxy = boxVolume(glm::vec3(0), glm::vec3(1));
    small.desc.fadeDistance = 0.5f;
    big.desc.proxy = sphereVolume(glm::vec3(0), 3.0f);
    big.desc.fadeDistance = 1.0f;
    // Added large first: the set evaluates the smaller influence volume first (4.9.5 "from small to big").
    ProbeSet set = setOf({big, small}, blue);
    ASSERT_EQ(set.localProbes()[0].proxy.shape, IBL_VOLUME_BOX);
    int partial = 0, inside = 0;
    for (glm::vec3 p : axisPoints()) {
        glm::vec4 expected = pseudoCode({small, big}, blue, p), got = composedMirrorLd(set, p);
        EXPECT_EQ(got, expected) << "z = " << p.z;
        EXPECT_LT(expected.w, 1.0f) << "alpha stays below 1: the distant probe always shows";
        partial += expected.w > 0.0f;
        inside += std::abs(p.z) < 0.5f;
    }
    // Inside the small box away from its fade: red 0.5, green 0.75 - 0.5 = 0.25, blue 0.25, alpha 0.75.
    EXPECT_EQ(composedMirrorLd(set, glm::vec3(0, 0, 0.25f)), glm::vec4(0.5f, 0.25f, 0.25f, 0.75f));
    EXPECT_GT(partial, 150);
    EXPECT_GT(inside, 10);
    std::printf("nested probes, visibility 0.5 / 0.75: %zu axis points equal to the pseudo-code\n",
                axisPoints().size());

    // The whole shading on both backends (the split sum scales the LD by DFG1 + DFG2 ~ 1/energy).
    RuntimeOptions options;
    options.diffuse = false;
    std::vector<ShadingPoint> points = mirrorPoints(axisPoints());
    std::vector<glm::vec4> shaded = evaluateCpu(set, points, options);
    for (std::size_t i = 0; i < points.size(); ++i) {
        glm::vec4 expected = pseudoCode({small, big}, blue, points[i].position);
        EXPECT_EQ(shaded[i].w, expected.w);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(shaded[i][c], expected[c], 2e-6f);
    }
    EXPECT_BACKENDS_AGREE(set, points, options);
}

TEST(VisibilityComposition, OrderDependenceAndTheSameLobeRule) {
    const glm::vec3 red(1, 0, 0), green(0, 1, 0), blue(0, 0, 1);
    // Two probes of the same influence volume: the set keeps the order of addition.
    Layer a{{}, red, 0.5f}, b{{}, green, 0.75f};
    a.desc.proxy = b.desc.proxy = boxVolume(glm::vec3(0), glm::vec3(2));
    a.desc.fadeDistance = b.desc.fadeDistance = 1.0f;
    ProbeSet ab = setOf({a, b}, blue), ba = setOf({b, a}, blue);
    int differ = 0;
    for (glm::vec3 p : axisPoints()) {
        glm::vec4 gotAb = composedMirrorLd(ab, p), gotBa = composedMirrorLd(ba, p);
        EXPECT_EQ(gotAb, pseudoCode({a, b}, blue, p)) << "z = " << p.z;
        EXPECT_EQ(gotBa, pseudoCode({b, a}, blue, p)) << "z = " << p.z;
        differ += gotAb != gotBa;
    }
    // Full weight: 0.5 red then 0.75 - 0.5 green; the other way 0.75 green and nothing of red (a < 0).
    EXPECT_EQ(composedMirrorLd(ab, glm::vec3(0)), glm::vec4(0.5f, 0.25f, 0.25f, 0.75f));
    EXPECT_EQ(composedMirrorLd(ba, glm::vec3(0)), glm::vec4(0.0f, 0.75f, 0.25f, 0.75f));
    EXPECT_GT(differ, 50) << "the composition depends on the order (4.9.5: order dependent)";

    // Erratum of 4.9.5: overlapping probes cover the same part of the lobe; ten of visibility 0.125 give
    // 0.125 (the previous rule gave 1.25 -> 1), and the distant probe keeps 0.875.
    std::vector<Layer> ten(10, Layer{{}, red, 0.125f});
    for (Layer& layer : ten)
        layer.desc.proxy = boxVolume(glm::vec3(0), glm::vec3(2));
    ten[3].colour = green;
    ProbeSet tenSet = setOf(ten, blue);
    EXPECT_EQ(composedMirrorLd(tenSet, glm::vec3(0)), glm::vec4(0.125f, 0.0f, 0.875f, 0.125f));
    std::printf("order (0.5, 0.75) vs (0.75, 0.5): %d of %zu axis points differ, each equal to the "
                "pseudo-code in its order; ten probes of 0.125 compose to 0.125\n",
                differ, axisPoints().size());
}

// ------------------------------------------------------------------------------------------------
// A room with a window: an axis-aligned box proxy whose capture sees the walls except a window in the +X
// wall, where the visibility is 0. Mirrors whose ray leaves through the window get the distant probe, the
// others the wall their ray hits.

const ProbeVolume kRoom = boxVolume(glm::vec3(0), glm::vec3(3, 1.5f, 2));

bool inWindow(glm::vec3 local) {
    return local.x > 2.999f && std::abs(local.y) < 0.8f && std::abs(local.z) < 1.2f;
}

// The capture from the room's centre: colour x visibility and the visibility.
CubeMap windowRoomCapture(int n) {
    CubeMap cube(n);
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                glm::vec3 d = glm::normalize(glm::vec3(cubeFaceDirection(f, (x + 0.5f) / n, (y + 0.5f) / n)));
                glm::vec3 hit = analyticHitLocal(kRoom, glm::vec3(0), d);
                cube.faces[f].at(x, y) =
                    inWindow(hit) ? glm::vec4(0.0f) : glm::vec4(kWallColors[wallOf(kRoom, hit)], 1.0f);
            }
    return cube;
}

// Whether the four level-0 texels a bilinear lookup in direction d reads are all window or all wall `wall`.
bool tapsAllSee(int n, glm::vec3 d, bool window, int wall) {
    CubeCoord c = cubeCoordFromDirection(d);
    float x = c.s * n - 0.5f, y = c.t * n - 0.5f;
    int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            glm::vec3 tap = glm::normalize(
                glm::vec3(cubeFaceDirection(c.face, (x0 + i + 0.5f) / n, (y0 + j + 0.5f) / n)));
            glm::vec3 hit = analyticHitLocal(kRoom, glm::vec3(0), tap);
            if (inWindow(hit) != window || (!window && wallOf(kRoom, hit) != wall)) return false;
        }
    return true;
}

TEST(VisibilityRoom, MirrorsSeeTheDistantProbeThroughTheWindowAndTheWallsElsewhere) {
    const int n = 64;
    ProbeSet set(bakeLd(makeCube(64, skyLike)), dfgTableFromImage(dfgLut()), ShCoefficients{});
    LocalProbeDesc desc;
    desc.proxy = kRoom;
    desc.fadeDistance = 0.25f;
    set.addLocalProbe(desc, ldPyramidFromChain(CubeMapChain{{windowRoomCapture(n)}}, MipMapping::Frostbite,
                                               ChainAlpha::PremultipliedVisibility));
    RuntimeParams params = makeRuntimeParams(set, RuntimeOptions{}, 1);

    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    int throughWindow = 0, onWalls = 0;
    double worstSky = 0.0, worstWall = 0.0;
    std::vector<ShadingPoint> points;
    while (points.size() < 4000) {
        glm::vec3 p = glm::vec3(u(rng), u(rng), u(rng)) * (glm::vec3(kRoom.extent) - glm::vec3(0.3f));
        glm::vec3 nrm = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
        glm::vec3 view = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
        if (glm::dot(nrm, view) < 0.05f) continue;
        glm::vec3 R = glm::normalize(glm::reflect(-view, nrm));
        points.push_back(makeShadingPoint(p, nrm, view, glm::vec3(1.0f), 1.0f, 0.0f));
        glm::vec3 hit = analyticHitLocal(kRoom, p, R);
        glm::vec3 lookup = glm::normalize(hit); // capture at the centre
        bool window = inWindow(hit);
        int wall = wallOf(kRoom, hit);
        if (!tapsAllSee(n, lookup, window, wall)) continue; // at the window's frame or a wall's edge
        ProbeSample s = composeSpecularLd(params, set.distantData().data(), set.localProbes().data(),
                                          set.localLdData().data(), p, R, R, R, 1.0f, 0.0f);
        if (window) {
            ++throughWindow;
            glm::vec3 sky = sampleLd(set.distantData().data(), params.distant, R, 0.0f);
            ASSERT_EQ(s.alpha, 0.0f);
            for (int c = 0; c < 3; ++c)
                worstSky = std::max(worstSky, double(std::abs(s.radiance[c] - sky[c]) / sky[c]));
        } else {
            ++onWalls;
            ASSERT_NEAR(s.alpha, 1.0f, 1e-6f); // the bilinear weights sum to 1 within rounding
            for (int c = 0; c < 3; ++c)
                worstWall = std::max(
                    worstWall, double(std::abs(s.radiance[c] - kWallColors[wall][c]) / kWallColors[wall][c]));
        }
    }
    std::printf("window room: %d mirrors through the window (max relative error to the distant probe %.2g), "
                "%d on walls (to the wall %.2g)\n",
                throughWindow, worstSky, onWalls, worstWall);
    EXPECT_GT(throughWindow, 100);
    EXPECT_GT(onWalls, 2000);
    EXPECT_LT(worstSky, 1e-6);
    EXPECT_LT(worstWall, 1e-5);
    RuntimeOptions options;
    EXPECT_BACKENDS_AGREE(set, points, options);
}

// ------------------------------------------------------------------------------------------------
// Probes without visibility compose as before it existed; the hard cases give stated results.

TEST(VisibilityCompatibility, AllVisibleIsBitIdenticalToNoVisibility) {
    // A room with fades, baked by the production LD preset, read without its alpha and with an alpha of 1
    // everywhere (which makes no visibility pyramid); points in, across and outside the influence at every
    // roughness.
    Executor executor = openclOrCpu();
    CubeMapChain chain = bakeSpecular(windowRoomCapture(32), SpecularSettings{}, executor);
    for (CubeMap& level : chain.levels)
        for (ImageRGBA& face : level.faces)
            for (glm::vec4& texel : face.pixels)
                texel.w = 1.0f;
    LocalProbeDesc desc;
    desc.proxy = kRoom;
    desc.captureOffset = glm::vec3(0.4f, -0.2f, 0.3f);
    desc.fadeDistance = 0.6f;
    CubeMap sky = makeCube(32, skyLike);
    ProbeSet plain = distantSet(sky), visible = distantSet(sky);
    plain.addLocalProbe(desc, ldPyramidFromChain(chain));
    visible.addLocalProbe(
        desc, ldPyramidFromChain(chain, MipMapping::Frostbite, ChainAlpha::PremultipliedVisibility));
    ASSERT_EQ(visible.localProbes()[0].hasVisibility, 0u);
    ASSERT_EQ(visible.localLdData(), plain.localLdData());
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), r01(0.0f, 1.0f);
    std::vector<ShadingPoint> points;
    for (int i = 0; i < 3000; ++i)
        points.push_back(makeShadingPoint(
            glm::vec3(u(rng), u(rng), u(rng)) * glm::vec3(3.5f, 2.0f, 2.5f),
            glm::vec3(u(rng), u(rng), u(rng)), glm::vec3(u(rng), u(rng), u(rng)),
            glm::vec3(r01(rng), r01(rng), r01(rng)), r01(rng) < 0.5f ? 1.0f : 0.0f, (i % 11) / 10.0f));
    RuntimeOptions options;
    std::vector<glm::vec4> a = evaluateCpu(plain, points, options), b = evaluateCpu(visible, points, options);
    int partial = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        ASSERT_EQ(std::memcmp(&a[i], &b[i], sizeof(glm::vec4)), 0) << "point " << i;
        partial += a[i].w > 0.0f && a[i].w < 1.0f;
    }
    EXPECT_GT(partial, 100) << "points in the fade";
    if (executor.usesOpenCL()) {
        OpenCLProbeEvaluator clPlain(executor.cl(), plain), clVisible(executor.cl(), visible);
        std::vector<glm::vec4> ca = clPlain.evaluate(points, options),
                               cb = clVisible.evaluate(points, options);
        for (std::size_t i = 0; i < points.size(); ++i)
            ASSERT_EQ(std::memcmp(&ca[i], &cb[i], sizeof(glm::vec4)), 0) << "OpenCL point " << i;
    }
    std::printf("alpha 1 everywhere vs none: %zu points bit-identical (CPU%s), %d in the fade\n",
                points.size(), executor.usesOpenCL() ? " and OpenCL" : "", partial);
    EXPECT_BACKENDS_AGREE(visible, points, options);
}

TEST(VisibilityHardCases, TransparentNaNNegativeAndAboveOne) {
    CubeMap sky = makeCube(16, skyLike);
    LocalProbeDesc desc;
    desc.proxy = kRoom;
    desc.fadeDistance = 0.5f;
    std::vector<ShadingPoint> points;
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int i = 0; i < 500; ++i)
        points.push_back(makeShadingPoint(
            glm::vec3(u(rng), u(rng), u(rng)) * glm::vec3(kRoom.extent), glm::vec3(u(rng), u(rng), u(rng)),
            glm::vec3(u(rng), u(rng), u(rng)), glm::vec3(0.8f), 1.0f, (i % 6) / 5.0f));
    RuntimeOptions options;
    ProbeSet distantOnly = distantSet(sky);
    const std::vector<glm::vec4> background = evaluateCpu(distantOnly, points, options);

    // Visibility 0 at every texel of every level: the probe is transparent, the result is the distant
    // probe's to the bit, alpha 0.
    Executor executor = openclOrCpu();
    CubeMapChain chain = bakeSpecular(windowRoomCapture(16), SpecularSettings{}, executor);
    CubeMapChain transparent = chain;
    for (CubeMap& level : transparent.levels)
        for (ImageRGBA& face : level.faces)
            for (glm::vec4& texel : face.pixels)
                texel = glm::vec4(0.0f);
    ProbeSet clear = distantSet(sky);
    clear.addLocalProbe(
        desc, ldPyramidFromChain(transparent, MipMapping::Frostbite, ChainAlpha::PremultipliedVisibility));
    std::vector<glm::vec4> out = evaluateCpu(clear, points, options);
    for (std::size_t i = 0; i < points.size(); ++i)
        ASSERT_EQ(std::memcmp(&out[i], &background[i], sizeof(glm::vec4)), 0) << "point " << i;
    EXPECT_BACKENDS_AGREE(clear, points, options);

    // NaN, -inf, negative and > 1 visibility: stored as 0, 0, 0 and 1, counted; every result finite.
    CubeMapChain bad = chain;
    for (CubeMap& level : bad.levels)
        for (ImageRGBA& face : level.faces)
            for (glm::vec4& texel : face.pixels)
                texel.w = 1.0f;
    std::size_t planted = 0;
    const float values[4] = {std::numeric_limits<float>::quiet_NaN(), -std::numeric_limits<float>::infinity(),
                             -0.5f, 7.0f};
    for (CubeMap& level : bad.levels)
        for (ImageRGBA& face : level.faces)
            for (std::size_t k = 0; k < face.pixels.size(); k += 3) {
                face.pixels[k].w = values[planted % 4];
                ++planted;
            }
    LdPyramid pyramid = ldPyramidFromChain(bad, MipMapping::Frostbite, ChainAlpha::PremultipliedVisibility);
    EXPECT_EQ(pyramid.visibilityTexelsClamped, planted);
    for (float v : pyramid.visibility)
        ASSERT_TRUE(v >= 0.0f && v <= 1.0f) << v;
    ProbeSet hostile = distantSet(sky);
    hostile.addLocalProbe(desc, pyramid);
    out = evaluateCpu(hostile, points, options);
    for (const glm::vec4& v : out)
        ASSERT_TRUE(std::isfinite(v.x + v.y + v.z + v.w) && v.w >= 0.0f && v.w <= 1.0f);
    EXPECT_BACKENDS_AGREE(hostile, points, options);
    std::printf("visibility 0 everywhere: %zu points equal to the distant probe alone; %zu bad visibility "
                "texels clamped and counted, results finite\n",
                points.size(), planted);

    // A distant pyramid with a visibility is refused (the distant probe is the background).
    LdPyramid distantWithVisibility =
        ldPyramidFromChain(chain, MipMapping::Frostbite, ChainAlpha::PremultipliedVisibility);
    EXPECT_THROW(ProbeSet(distantWithVisibility, dfgTableFromImage(dfgLut()), ShCoefficients{}), Error);
}

// ------------------------------------------------------------------------------------------------
// KTX2: the key "iblbake.visibility" says the alpha is a premultiplied visibility; files without it read
// as before.

TEST(VisibilityKtx2, KeyReadsTheAlphaAsVisibilityAndOlderFilesReadAsBefore) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("iblbake_visibility_ktx2_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    CubeMapChain chain;
    for (int n = 8; n >= 1; n /= 2) {
        CubeMap level(n);
        for (int f = 0; f < 6; ++f)
            for (glm::vec4& texel : level.faces[f].pixels) {
                const float v = float((f + n) % 3) * 0.5f; // 0, 0.5, 1: exact in half floats
                texel = glm::vec4(glm::vec3(0.25f, 0.5f, 0.75f) * v, v);
            }
        chain.levels.push_back(level);
    }
    writeKtx2Cube(dir / "visible.ktx2", chain, Ktx2Format::RGBA16F,
                  {{kVisibilityKey, kVisibilityPremultipliedAlpha}});
    writeKtx2Cube(dir / "older.ktx2", chain, Ktx2Format::RGBA16F, {});
    writeKtx2Cube(dir / "unknown.ktx2", chain, Ktx2Format::RGBA16F, {{kVisibilityKey, "straight"}});
    writeKtx2Cube(dir / "packed.ktx2", chain, Ktx2Format::B10G11R11,
                  {{kVisibilityKey, kVisibilityPremultipliedAlpha}});

    LdPyramid expected =
        ldPyramidFromChain(chain, MipMapping::Frostbite, ChainAlpha::PremultipliedVisibility);
    LdPyramid visible = loadLdKtx2(dir / "visible.ktx2");
    ASSERT_FALSE(visible.visibility.empty());
    EXPECT_EQ(visible.visibility, expected.visibility);
    EXPECT_EQ(visible.data, expected.data);
    LdPyramid older = loadLdKtx2(dir / "older.ktx2");
    EXPECT_TRUE(older.visibility.empty()) << "no key: the alpha is not read, as before";
    EXPECT_EQ(older.data, ldPyramidFromChain(chain).data);
    for (const char* name : {"unknown.ktx2", "packed.ktx2"}) {
        try {
            loadLdKtx2(dir / name);
            ADD_FAILURE() << name << " loaded";
        } catch (const Error& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find(name), std::string::npos) << what;
            EXPECT_NE(what.find(kVisibilityKey), std::string::npos) << what;
            std::printf("%s\n", what.c_str());
        }
    }
    std::filesystem::remove_all(dir);
}

} // namespace
