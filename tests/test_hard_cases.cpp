// Inputs where bakers usually break, across every stage. Nothing may produce NaN/Inf, crash, or throw
// where a result exists; energy is kept where it must be. This file and the tests named below are the
// hard-case suite (ctest label "hard": `ctest --test-dir build -L hard`, tests/CMakeLists.txt).
//
// Checklist (issue 7, item 3): each case, the tests that cover it, what they bound.
// - Perceptual roughness exactly 0 and 1:
//     DfgLut.ExactCornersAreFinite (integrator at r = 0, 1e-7, 1; mirror DFG1 + DFG2 = 1 within 1e-5),
//     HardCases.DfgLutAtExactCorners (baked LUT looked up at r = 0 and 1: finite, in [0, 1], DFG1 + DFG2
//     <= 1 + 1e-3), Specular.MirrorLevelIsTheSourceAndMappingIsEq63, Furnace.MetalF0OneWithin2PercentFor
//     EveryRoughness (runtime furnace within 2% at every roughness), Degenerate.EveryCaseFinite (runtime
//     at r = -0.5, 0, 1e-4, 1, 3).
// - NoV exactly 0 and 1 in the LUT: DfgLut.ExactCornersAreFinite (NoV = 0, 1e-7, 1),
//     HardCases.DfgLutAtExactCorners, Degenerate.EveryCaseFinite (view perpendicular to the normal).
// - A sun 10^6 brighter than the sky in less than one texel: HardCases.SubTexelSunKeepsItsEnergyThroughEvery
//     Stage (a lat-long pixel of 1/50 of a cube texel; energy through ingest within 0.5%, irradiance
//     energy pi x radiance energy within 0.2%), Specular.BrightSunStaysFiniteAndBounded,
//     IngestResample.OnePixelSunKeepsItsEnergy (within 1%), Sun.OneTexelSunOnFlatSkyIsRecoveredExactly,
//     RoughLayers.SunAMillionTimesTheSkyKeepsEachLayersEnergy (every rough layer within 1%; 0.09%).
// - Black except one texel: HardCases.BlackExceptOneTexelStaysFiniteAndShKeepsItsEnergy,
//     Irradiance.SingleBrightTexelIsExact, Sh.SingleBrightTexel.
// - One bright texel at every face size 1..256: HardCases.OneBrightTexelAtEveryFaceSize (test_hard_cases_
//     seams.cpp: every level finite and >= 0, its brightest texel the one nearest the source texel).
// - A sun exactly on a cube edge and corner: HardCases.SunOnACubeEdgeAndCornerStaysSymmetric (the faces
//     sharing it get equal energy within 1% at every level, OpenCL and CPU).
// - All-zero environment: HardCases.AllZeroEnvironmentBakesToZero (every stage exactly 0, no sun).
// - NaN/Inf/negative/denormal pixels: IngestFile.RepairsAndCountsBadPixels (repaired and counted, all
//     finite and >= 0), HardCases.DenormalAndHugeValuesStayFinite, Ktx2Formats.NonFiniteValuesAreRepaired
//     AndNeverStored.
// - Values above the half-float range: HardCases.ValuesPastHalfRangeAreClampedAndCountedInKtx2,
//     Ktx2Formats.ClampsToTheFormatRangeAndCountsClampedTexels, Cli.HalfOutput.
// - 1x1 and 2x2 faces, the 1x1 last level: Specular.TinyFacesAndBadSizes (1x1 and 2x2 sources; a
//     constant 2x2 within 2e-4), HardCases.LastLevelIsOneTexelAndAWeightedMeanOfTheSource,
//     Degenerate.EveryCaseFinite (the runtime at roughness 1 reads the 1x1 level),
//     RoughLayers.WhiteFurnaceEveryLayerEveryTexel (rough layers of 1-, 2-, 16- and 32-px faces).
// - Non-power-of-two lat-long inputs: HardCases.NonPowerOfTwoLatLongFiles (1000x500 and 37x19: a constant
//     stays constant within 1e-5, energy within 0.5%), IngestResample.EnergyIsPreserved (face size 45).
// - Extreme aspect ratios rejected clearly: IngestFile.UnknownLayoutIsAnErrorNamingTheFile (7x3 and
//     80x2), HardCases.NonPowerOfTwoLatLongFiles (37x19 auto-detection asks for --layout).
// - SH of a delta with and without windowing: ShWindow.DeltaWithAndWithoutWindow (every window: finite,
//     the automatic one leaves E >= 0), HardCases.DeltaShKeepsItsEnergyUnderEveryWindow (L0 unchanged),
//     HardCases.BlackExceptOneTexelStaysFiniteAndShKeepsItsEnergy.
// - Parallax rays parallel to box faces, shading points on and outside the proxy, zero-size and
//     degenerate proxies: Parallax.BoxAndSphereIntersectionsAndParallelRays, Degenerate.EveryCaseFinite
//     (zero-size box and sphere, zero-volume influence, capture point on the wall, points on corners,
//     inside, outside and far away), Rooms.BoxProxyMirrorReflectsTheWallItsRayHits.
// - Very large and very small calibration factors: HardCases.TinyAndHugeCalibrationFactors (1e-30 ..
//     1e30: every stage finite, calibration undoes the pre-scale within 1e-5),
//     Calibration.UnusableValuesAreOneLineErrorsNamingTheOption, CalibrateCli.ExactFactorsScaleEveryPixel.
// - Damaged files (issue 7, item 5): DamagedInputs.* (HDR/EXR/PNG/KTX2), Ktx2Reader.*.
// - Hostile inputs (issue 17): HostileInputs.* (headers claiming huge sizes, devices, FIFOs, symlink loops,
//     oversized documents, out-of-range values, outputs leaving the scene's directory),
//     FullAndReadOnlyDisks.* (a full and a read-only tmpfs: the output and the system's reason named).
// - Energy conservation: IngestResample.EnergyIsPreserved, Sh.ConstantEnvironmentIsL00OnlyAndIrradiancePiL,
//     DfgLut.EnergyBoundedAndMirrorLimit, Specular.WhiteFurnaceEveryLevelEveryTexel,
//     Furnace.MetalF0OneWithin2PercentForEveryRoughness, CalibrateCli.ExtractSunWritesTheLightAndConserves
//     Energy, and the energy statements of this file.
// - Area lights: shading points on the light, on its plane, behind it, inside a sphere light, at grazing
//     normals and views, zero vectors: AreaLights.HardCasesAreFinite (finite and >= 0, exactly 0 where the
//     brute force is).
// - A local probe capture's alpha (issue 16): SceneVisibility.AlphaNanNegativeAndOverOneAreRepairedAndCounted
//     (NaN and negative -> transparent, > 1 -> 1, counted in the manifest and the bake report, the loaded
//     set finite), SceneVisibility.AlphaZeroEverywhereIsTransparent (the distant probe alone at every point),
//     SpecularVisibilityHardCases.* (the filter's own).
#include "test_support.h"

#include <iblbake/baker/calibration.h>
#include <iblbake/baker/dfg_lut.h>
#include <iblbake/baker/environment_stats.h>
#include <iblbake/baker/irradiance.h>
#include <iblbake/baker/sh.h>
#include <iblbake/baker/specular.h>
#include <iblbake/baker/sun.h>
#include <iblbake/core/error.h>
#include <iblbake/ktx2/ktx2.h>
#include <iblbake/runtime/runtime.h>

#include <probe.h>

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <limits>
#include <numbers>

namespace fs = std::filesystem;

namespace {

using namespace ibl;
using namespace ibl::test;

void expectFinite(const ShRgb& sh, const char* what) {
    for (const glm::dvec3& c : sh)
        ASSERT_TRUE(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z)) << what;
}

// Every stage on one environment: the specular chain, the irradiance cube (sampled and from SH), the SH
// with the automatic window, and sun detection.
void bakeEverything(const CubeMap& env, const char* what) {
    for (Executor executor : {Executor::cpu(), openclOrCpu()}) {
        for (const CubeMap& level : bakeSpecular(env, SpecularSettings{}, executor).levels)
            expectFiniteNonNegative(level, what);
        IrradianceSettings irradiance;
        irradiance.faceSize = 8;
        expectFiniteNonNegative(bakeIrradianceCube(env, irradiance, executor), what);
    }
    DiffuseSH sh = bakeDiffuseSH(env, ShWindowSettings{});
    expectFinite(sh.radiance, what);
    expectFinite(sh.irradiance, what);
    expectFiniteNonNegative(irradianceCubeFromSH(sh.irradiance, 8), what);
    SunDetection sun = detectSun(env);
    EXPECT_TRUE(std::isfinite(sun.peakLuminance)) << what;
}

TEST(HardCases, AllZeroEnvironmentBakesToZero) {
    CubeMap black = makeCube(16, [](glm::dvec3) { return glm::dvec3(0.0); });
    bakeEverything(black, "all zero");
    for (const CubeMap& level : bakeSpecular(black, SpecularSettings{}, Executor::cpu()).levels)
        for (const ImageRGBA& face : level.faces)
            for (const glm::vec4& p : face.pixels)
                ASSERT_EQ(glm::vec3(p), glm::vec3(0.0f));
    EXPECT_FALSE(detectSun(black).found);
}

TEST(HardCases, BlackExceptOneTexelStaysFiniteAndShKeepsItsEnergy) {
    CubeMap env = makeCube(16, [](glm::dvec3) { return glm::dvec3(0.0); });
    env.faces[2].at(5, 9) = glm::vec4(1e6f, 1e6f, 1e6f, 1.0f);
    bakeEverything(env, "one texel");
    // The irradiance from SH integrates the texel's energy exactly: E at its own direction is
    // L * solid angle (band-limited, so allow the L2 truncation: > half and < twice).
    DiffuseSH sh = bakeDiffuseSH(env, ShWindowSettings{false, ShWindow::None, {}});
    glm::dvec3 d = texelCentre(2, 5, 9, 16);
    double expected = 1e6 * cubeTexelSolidAngle(5, 9, 16);
    double got = evalPrescaledSH(sh.irradiance, d).y;
    EXPECT_GT(got, 0.5 * expected);
    EXPECT_LT(got, 2.0 * expected);
}

TEST(HardCases, DenormalAndHugeValuesStayFinite) {
    const float denormal = std::numeric_limits<float>::denorm_min() * 7.0f;
    CubeMap env = makeCube(8, [&](glm::dvec3 d) { return glm::dvec3(d.y > 0.0 ? denormal : 1e30); });
    bakeEverything(env, "denormals and 1e30");
}

TEST(HardCases, TinyAndHugeCalibrationFactors) {
    auto sky = [](glm::dvec3 d) { return glm::dvec3(0.5 + 0.5 * d.y); };
    CalibrationSettings toTenThousandLux;
    toTenThousandLux.source = CalibrationSource::Illuminance;
    toTenThousandLux.value = 10000.0;
    const double unscaledFactor = computeCalibration(makeCube(8, sky), toTenThousandLux).factor;
    for (double factor : {1e-30, 1e-12, 1e12, 1e30}) {
        CubeMap env = makeCube(8, sky);
        applyCalibration(env, factor);
        bakeEverything(env, "calibrated");
        // Calibrating the pre-scaled map to the same illuminance undoes the pre-scale exactly.
        CalibrationRecord record = computeCalibration(env, toTenThousandLux);
        ASSERT_TRUE(std::isfinite(record.factor) && record.factor > 0.0) << factor;
        EXPECT_NEAR(record.factor * factor / unscaledFactor, 1.0, 1e-5) << factor;
    }
}

TEST(HardCases, ValuesPastHalfRangeAreClampedAndCountedInKtx2) {
    CubeMap env = makeCube(4, [](glm::dvec3) { return glm::dvec3(1e6); });
    CubeMapChain chain = bakeSpecular(env, SpecularSettings{}, Executor::cpu());
    fs::path dir = fs::temp_directory_path() / ("iblbake_hard_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    Ktx2WriteStats stats = writeKtx2Cube(dir / "big.ktx2", chain, Ktx2Format::RGBA16F, {});
    EXPECT_EQ(stats.clampedTexels, 6u * (16 + 4 + 1));
    for (const auto& level : readKtx2(dir / "big.ktx2").levels)
        for (const ImageRGBA& face : level)
            for (const glm::vec4& p : face.pixels)
                ASSERT_EQ(p.x, 65504.0f);
    fs::remove_all(dir);
}

constexpr double kPi = std::numbers::pi;

// Mean radiance over the sphere (solid-angle weighted, luminance) of a cube.
double meanLuminance(const CubeMap& cube) {
    return computeEnvironmentStats(cube).meanLuminance;
}

TEST(HardCases, DfgLutAtExactCorners) {
    DfgSettings settings;
    settings.size = 16;
    settings.sampleCount = 256;
    for (Executor executor : {Executor::cpu(), openclOrCpu()}) {
        const DfgTable table = dfgTableFromImage(bakeDfgLut(settings, executor));
        for (float NoV : {0.0f, 1.0f})
            for (float roughness : {0.0f, 1.0f}) {
                const glm::vec3 dfg(dfgLookup(table.data.data(), table.size, NoV, roughness));
                for (int c = 0; c < 3; ++c) {
                    EXPECT_TRUE(std::isfinite(dfg[c])) << NoV << " " << roughness;
                    EXPECT_GE(dfg[c], 0.0f) << NoV << " " << roughness;
                    EXPECT_LE(dfg[c], 1.0f + 1e-3f) << NoV << " " << roughness;
                }
                // Energy: a white furnace (f0 = f90 = 1) reflects DFG1 + DFG2, never more than it receives.
                EXPECT_LE(dfg.x + dfg.y, 1.0f + 1e-3f) << NoV << " " << roughness;
            }
        // Smooth and seen head-on: nearly a mirror (the corner texel centre is at r = 1/32), little lost.
        const glm::vec3 smooth(dfgLookup(table.data.data(), table.size, 1.0f, 0.0f));
        EXPECT_GT(smooth.x + smooth.y, 0.97f);
    }
}

TEST(HardCases, SubTexelSunKeepsItsEnergyThroughEveryStage) {
    // A 1024x512 lat-long pixel near the equator covers ~3.8e-5 sr; a 32-texel cube face texel ~2e-3 sr.
    ImageRGBA latlong(1024, 512);
    for (glm::vec4& p : latlong.pixels)
        p = glm::vec4(1.0f, 1.0f, 1.0f, 1.0f);
    latlong.at(300, 200) = glm::vec4(1e6f, 1e6f, 1e6f, 1.0f);
    const CubeMap env = resampleLatLongToCube(latlong, 32, LatLongPixels::Centre);
    const double sourceMean = computeLatLongStats(latlong, LatLongPixels::Centre).meanLuminance;
    EXPECT_NEAR(meanLuminance(env) / sourceMean, 1.0, 0.005);
    bakeEverything(env, "sub-texel sun");
    EXPECT_TRUE(detectSun(env).found);
    // Irradiance energy: the integral of E(n) over all normals is pi times the integral of the radiance
    // (each direction's cosine lobe integrates to pi); the cubes store E / pi, so their mean over the
    // sphere is the source's mean radiance, for the sampled cube and the SH alike.
    for (Executor executor : {Executor::cpu(), openclOrCpu()}) {
        IrradianceSettings irradiance;
        irradiance.faceSize = 16;
        EXPECT_NEAR(meanLuminance(bakeIrradianceCube(env, irradiance, executor)) / sourceMean, 1.0, 2e-3);
    }
    const DiffuseSH sh = bakeDiffuseSH(env, ShWindowSettings{false, ShWindow::None, {}});
    EXPECT_NEAR(meanLuminance(irradianceCubeFromSH(sh.irradiance, 16)) / sourceMean, 1.0, 2e-3);
}

TEST(HardCases, LastLevelIsOneTexelAndAWeightedMeanOfTheSource) {
    const CubeMap env =
        makeCube(16, [](glm::dvec3 d) { return glm::dvec3(0.1 + d.y * d.y + 4.0 * std::max(0.0, d.x)); });
    float lowest = std::numeric_limits<float>::max(), highest = 0.0f;
    for (const ImageRGBA& face : env.faces)
        for (const glm::vec4& p : face.pixels) {
            lowest = std::min(lowest, p.x);
            highest = std::max(highest, p.x);
        }
    for (Executor executor : {Executor::cpu(), openclOrCpu()}) {
        const CubeMapChain chain = bakeSpecular(env, SpecularSettings{}, executor);
        ASSERT_EQ(chain.levels.back().faceSize, 1);
        // Pre-filtering takes normalized weighted means of non-negative radiance: every value of the
        // last level lies between the source's extremes (up to fp32 rounding).
        for (const ImageRGBA& face : chain.levels.back().faces) {
            ASSERT_EQ(face.pixels.size(), 1u);
            EXPECT_TRUE(std::isfinite(face.pixels[0].x));
            EXPECT_GE(face.pixels[0].x, lowest * (1.0f - 1e-4f));
            EXPECT_LE(face.pixels[0].x, highest * (1.0f + 1e-4f));
        }
        // ... and the runtime accepts the chain down to 1x1.
        EXPECT_NO_THROW(ldPyramidFromChain(chain));
    }
}

// Writes a float RGB EXR with OpenImageIO.
void writeExr(const fs::path& path, const ImageRGBA& image) {
    std::vector<float> rgb;
    for (const glm::vec4& p : image.pixels)
        rgb.insert(rgb.end(), {p.x, p.y, p.z});
    auto out = OIIO::ImageOutput::create(path.string());
    ASSERT_TRUE(out && out->open(path.string(),
                                 OIIO::ImageSpec(image.width, image.height, 3, OIIO::TypeDesc::FLOAT)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, rgb.data()));
    ASSERT_TRUE(out->close());
}

TEST(HardCases, NonPowerOfTwoLatLongFiles) {
    const fs::path dir = fs::temp_directory_path() / ("iblbake_hard_npot_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    struct Case {
        int width, height;
        EnvLayout layout; // 37x19 is not 2:1, so the layout must be given
        int faceSize;     // width / 4 to the nearest power of two
    };
    for (const Case& c : {Case{1000, 500, EnvLayout::Auto, 256}, Case{37, 19, EnvLayout::LatLong, 8}}) {
        const std::string what = std::to_string(c.width) + "x" + std::to_string(c.height);
        const fs::path constantFile = dir / ("constant_" + what + ".exr");
        ImageRGBA constant(c.width, c.height);
        for (glm::vec4& p : constant.pixels)
            p = glm::vec4(2.0f, 2.0f, 2.0f, 1.0f);
        writeExr(constantFile, constant);
        IngestSettings settings;
        settings.layout = c.layout;
        const SourceEnvironment env = ingestEnvironment({constantFile}, settings);
        EXPECT_EQ(env.report.faceSize, c.faceSize) << what;
        for (const ImageRGBA& face : env.cube.faces)
            for (const glm::vec4& p : face.pixels)
                ASSERT_NEAR(p.x, 2.0f, 2e-5f) << what;
        // A bright pixel off the grid's symmetry lines: its energy arrives in the cube.
        ImageRGBA spot = constant;
        spot.at(c.width / 3, c.height / 3) = glm::vec4(1e4f, 1e4f, 1e4f, 1.0f);
        const fs::path spotFile = dir / ("spot_" + what + ".exr");
        writeExr(spotFile, spot);
        const SourceEnvironment spotEnv = ingestEnvironment({spotFile}, settings);
        EXPECT_NEAR(meanLuminance(spotEnv.cube) /
                        computeLatLongStats(spot, *spotEnv.report.latLongPixels).meanLuminance,
                    1.0, 0.005)
            << what;
        bakeEverything(spotEnv.cube, what.c_str());
    }
    // Left to detection, 37x19 is refused with a message naming the file, its size and the way out.
    try {
        ingestEnvironment({dir / "constant_37x19.exr"}, IngestSettings{});
        ADD_FAILURE() << "37x19 was accepted without a layout";
    } catch (const SettingError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("constant_37x19.exr"), std::string::npos) << message;
        EXPECT_NE(message.find("37x19"), std::string::npos) << message;
        EXPECT_EQ(e.setting(), "layout") << message; // the CLI names it --layout, a scene its key
    }
    fs::remove_all(dir);
}

TEST(HardCases, DeltaShKeepsItsEnergyUnderEveryWindow) {
    CubeMap delta = makeCube(16, [](glm::dvec3) { return glm::dvec3(0.0); });
    delta.faces[0].at(7, 3) = glm::vec4(1e6f, 1e6f, 1e6f, 1.0f);
    const DiffuseSH none = bakeDiffuseSH(delta, ShWindowSettings{false, ShWindow::None, {}});
    // The pre-scaled constant term is the mean irradiance over all normals: pi x the mean radiance.
    EXPECT_NEAR(none.irradiance[0].y / (kPi * meanLuminance(delta)), 1.0, 1e-3);
    std::vector<ShWindowSettings> windows = {ShWindowSettings{}};
    for (ShWindow w : {ShWindow::Sloan, ShWindow::Hanning, ShWindow::Lanczos})
        windows.push_back({false, w, std::nullopt});
    for (const ShWindowSettings& settings : windows) {
        const DiffuseSH windowed = bakeDiffuseSH(delta, settings);
        expectFinite(windowed.irradiance, "windowed delta");
        // Windows scale bands 1 and 2 only (w0 = 1): the energy is unchanged.
        EXPECT_NEAR(windowed.irradiance[0].y / none.irradiance[0].y, 1.0, 1e-12)
            << shWindowName(settings.window);
        EXPECT_EQ(windowed.radianceRaw[0], none.radianceRaw[0]);
    }
}

} // namespace
