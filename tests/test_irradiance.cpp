// The irradiance cube (stores E / pi): closed forms, the brute-force reference on the real HDRIs,
// OpenCL/CPU agreement, and the `iblbake diffuse` command end to end.
#include "cli_runner.h"

#include <iblbake/baker/exr_output.h>
#include <iblbake/baker/ingest.h>
#include <iblbake/baker/irradiance.h>
#include <iblbake/baker/sh.h>
#include <iblbake/core/error.h>
#include <iblbake/ktx2/ktx2.h>

#include <cube.h>

#include "test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace {

using namespace ibl;
using namespace ibl::test;

constexpr double kPi = 3.14159265358979323846;

std::vector<Executor> backends() {
    std::vector<Executor> e{Executor::cpu()};
    Executor cl = openclOrCpu();
    if (cl.usesOpenCL()) e.push_back(cl);
    return e;
}

// A constant environment L: every texel stores L (E / pi), i.e. irradiance pi L, with both methods and
// both backends. Trilinear lookups of a constant are exact; what remains is fp32 summation of 512
// samples (relative ~1e-6), so 1e-5.
TEST(Irradiance, ConstantEnvironment) {
    const glm::vec3 L(0.75f, 1.5f, 3.0f);
    CubeMap source = makeCube(64, [&](const glm::dvec3&) { return L; });
    std::vector<CubeMap> cubes;
    for (const Executor& e : backends())
        cubes.push_back(bakeIrradianceCube(source, IrradianceSettings{}, e));
    DiffuseSH sh = bakeDiffuseSH(source, {});
    std::uint64_t clamped = 99;
    cubes.push_back(irradianceCubeFromSH(sh.irradiance, 32, &clamped));
    EXPECT_EQ(clamped, 0u);
    for (const CubeMap& cube : cubes) {
        ASSERT_EQ(cube.faceSize, 32);
        for (const ImageRGBA& face : cube.faces)
            for (const glm::vec4& p : face.pixels)
                for (int c = 0; c < 3; ++c)
                    ASSERT_NEAR(kPi * p[c], kPi * L[c], 1e-5 * kPi * L[c]);
    }
}

// One texel of radiance B on black: it is split off as bright and integrated exactly, so every output
// texel holds B omega max(0, n.d) / pi. The residual keeps the threshold (16 x the mean luminance, i.e.
// 16 omega / (4 pi) = 0.26% of the texel's energy at 32 px) and goes through filtered sampling, where a
// sample reading a level rounded down sees up to 4x its footprint's share of it: up to ~1% of the peak
// B omega / pi (measured 0.53%). A wrong normalization or cosine would be off by tens of percent.
TEST(Irradiance, SingleBrightTexelIsExact) {
    const int n = 32, face = 1, tx = 7, ty = 22;
    const glm::dvec3 B(4e4, 1e4, 2e4);
    CubeMap source(n);
    source.faces[face].at(tx, ty) = glm::vec4(glm::vec3(B), 1.0f);
    const glm::dvec3 d = texelCentre(face, tx, ty, n);
    const double omega = texelSolidAngle(tx, ty, n);
    for (const Executor& e : backends()) {
        CubeMap cube = bakeIrradianceCube(source, IrradianceSettings{}, e);
        for (int f = 0; f < 6; ++f)
            for (int y = 0; y < 32; ++y)
                for (int x = 0; x < 32; ++x) {
                    double cosine = std::max(0.0, glm::dot(texelCentre(f, x, y, 32), d));
                    for (int c = 0; c < 3; ++c)
                        ASSERT_NEAR(cube.faces[f].at(x, y)[c], B[c] * omega * cosine / kPi,
                                    1e-2 * B[c] * omega / kPi)
                            << e.description() << " face " << f << " " << x << "," << y;
                }
    }
}

// L = max(0, w.d): E(n) = (2/3) ((pi - theta) cos theta + sin theta). The sampled cube stays within 1%
// relative mean error of it (pre-filtered lookups blur the lobe's horizon kink a little).
TEST(Irradiance, ClampedCosineLobe) {
    const glm::dvec3 d = glm::normalize(glm::dvec3(-0.6, 0.2, 0.7));
    CubeMap source =
        makeCube(128, [&](const glm::dvec3& w) { return glm::vec3(float(std::max(0.0, glm::dot(w, d)))); });
    CubeMap exact(32);
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x) {
                double t = glm::dot(texelCentre(f, x, y, 32), d), theta = std::acos(std::clamp(t, -1.0, 1.0));
                exact.faces[f].at(x, y) =
                    glm::vec4(float((2.0 / 3.0) * ((kPi - theta) * t + std::sin(theta)) / kPi));
            }
    double error =
        relativeMeanAbsError(bakeIrradianceCube(source, IrradianceSettings{}, openclOrCpu()), exact);
    std::printf("clamped-cosine lobe: sampled cube relative mean error %.5f\n", error);
    EXPECT_LT(error, 0.01);
}

TEST(Irradiance, OpenCLAgreesWithCpu) {
    Executor cl = openclOrCpu();
    if (!cl.usesOpenCL()) GTEST_SKIP() << "no OpenCL device";
    CubeMap source = makeCube(64, [](const glm::dvec3& w) {
        glm::vec3 sky = glm::vec3(0.4f, 0.6f, 1.0f) * float(0.5 + 0.5 * std::max(w.y, 0.0));
        float sun =
            float(std::pow(std::max(glm::dot(w, glm::normalize(glm::dvec3(0.5, 0.4, 0.6))), 0.0), 400.0));
        return (w.y > 0 ? sky : glm::vec3(0.1f, 0.08f, 0.05f)) + glm::vec3(5e3f, 4e3f, 3e3f) * sun;
    });
    for (int size : {32, 5}) {
        IrradianceSettings s;
        s.faceSize = size;
        CubeMap a = bakeIrradianceCube(source, s, Executor::cpu());
        CubeMap b = bakeIrradianceCube(source, s, cl);
        // Same functions and tables; FMA contraction and summation order differ between the compilers.
        EXPECT_LT(relativeMeanAbsError(b, a), 1e-5) << size;
    }
}

TEST(Irradiance, BadSizesAndMethods) {
    CubeMap source = makeCube(12, [](const glm::dvec3&) { return glm::vec3(1.0f); });
    EXPECT_THROW(bakeIrradianceCube(source, IrradianceSettings{}, Executor::cpu()), Error); // not 2^k
    IrradianceSettings zero;
    zero.faceSize = 0;
    EXPECT_THROW(bakeIrradianceCube(makeCube(8, [](const glm::dvec3&) { return glm::vec3(1.0f); }), zero,
                                    Executor::cpu()),
                 Error);
    EXPECT_EQ(parseIrradianceMethod("sh"), IrradianceMethod::SH);
    EXPECT_THROW(parseIrradianceMethod("exact"), Error);
    // A 1-texel source still works (one pyramid level).
    CubeMap one = bakeIrradianceCube(makeCube(1, [](const glm::dvec3&) { return glm::vec3(2.0f); }),
                                     IrradianceSettings{}, openclOrCpu());
    EXPECT_NEAR(one.faces[0].at(0, 0).x, 2.0f, 2e-5f);
}

// ---- Real HDRIs ----------------------------------------------------------------------------------

class IrradianceHdri : public SharedHdriTest {};

// Sampled cube (production preset, 32-px faces) against the brute force (every texel of a 128-px source,
// every output texel, fp64): within 1% relative mean error. Draft and reference are printed for the
// error-vs-cost curve, and the SH method for comparison (its error is the L2 truncation).
TEST_P(IrradianceHdri, ProductionWithin1PercentOfBruteForce) {
    IngestSettings ingest;
    ingest.sourceFaceSize = 128;
    CubeMap source = ingestEnvironment({hdriPath(GetParam())}, ingest).cube;
    CubeMap ref = referenceIrradianceCube(source, 32);
    Executor executor = openclOrCpu();
    std::printf("%-26s", GetParam());
    for (Quality q : {Quality::Draft, Quality::Production, Quality::Reference}) {
        IrradianceSettings s;
        s.quality = q;
        auto start = std::chrono::steady_clock::now();
        CubeMap cube = bakeIrradianceCube(source, s, executor);
        double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        double error = relativeMeanAbsError(cube, ref);
        std::printf(" %s(%u) %.4f %.0fms", qualityName(q), irradianceSamplesFor(s), error, ms);
        if (q != Quality::Draft) {
            EXPECT_LT(error, 0.01) << GetParam() << " " << qualityName(q);
        }
        for (const ImageRGBA& face : cube.faces)
            for (const glm::vec4& p : face.pixels)
                for (int c = 0; c < 3; ++c)
                    ASSERT_TRUE(std::isfinite(p[c]) && p[c] >= 0.0f);
    }
    DiffuseSH sh = bakeDiffuseSH(source, {});
    std::printf(" sh(windowed %s) %.4f\n", shWindowName(sh.window.window),
                relativeMeanAbsError(irradianceCubeFromSH(sh.irradiance, 32), ref));
}

INSTANTIATE_TEST_SUITE_P(SharedHdris, IrradianceHdri, ::testing::ValuesIn(kSharedHdris), hdriTestName);

// ---- CLI -----------------------------------------------------------------------------------------

using test::entryCount;
using test::freshTempDir;
using test::lineCount;
using test::runCli;

// A small lat-long EXR: sky gradient and a bright spot.
fs::path writeSyntheticLatLong(const fs::path& dir) {
    ImageRGBA img(64, 32);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 64; ++x) {
            float v = 1.0f - float(y) / 32.0f;
            img.at(x, y) = glm::vec4(0.2f + v, 0.3f + v, 0.5f + v, 1.0f);
        }
    img.at(40, 8) = glm::vec4(5000.0f, 4000.0f, 3000.0f, 1.0f);
    fs::path file = dir / "sky.exr";
    writeExr(file, img, ExrOutputOptions{});
    return file;
}

TEST(DiffuseCli, WritesJsonAndCube) {
    fs::path dir = freshTempDir("diffuse_ok");
    fs::path input = writeSyntheticLatLong(dir);
    fs::path json = dir / "probe.json", cube = dir / "irr.ktx2";
    test::CliRun r = runCli("diffuse " + input.string() + " -o " + json.string() + " --irradiance-cube " +
                            cube.string() + " --size 16 --irradiance-size 8 --backend cpu --timing");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("min irradiance before"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("timing: stage  irradiance "), std::string::npos) << r.out;
    std::ifstream in(json);
    nlohmann::json doc = nlohmann::json::parse(in);
    EXPECT_EQ(doc["schemaVersion"], 1);
    EXPECT_EQ(doc["sh"]["order"], 2);
    EXPECT_EQ(doc["sh"]["radiance"].size(), 9u);
    EXPECT_EQ(doc["sh"]["irradiance"].size(), 9u);
    EXPECT_EQ(doc["sh"]["irradiance"][0].size(), 3u);
    EXPECT_EQ(doc["units"], "relative (input values, uncalibrated)");
    EXPECT_EQ(doc["colorSpace"], "lin_rec709");
    EXPECT_NE(doc["sh"]["irradianceConvention"].get<std::string>().find("irradianceSH"), std::string::npos);
    EXPECT_EQ(doc["sh"]["window"]["requested"], "auto");
    // irradianceOverPi = irradiance / pi, and the mean of E is A0 k0 L00 = c0.
    EXPECT_NEAR(doc["sh"]["irradianceOverPi"][0][1].get<double>() * kPi,
                doc["sh"]["irradiance"][0][1].get<double>(),
                1e-9 * doc["sh"]["irradiance"][0][1].get<double>());
    EXPECT_NEAR(doc["sh"]["minIrradiance"]["mean"][1].get<double>(),
                doc["sh"]["irradiance"][0][1].get<double>(),
                1e-9 * doc["sh"]["irradiance"][0][1].get<double>());
    for (int c = 0; c < 3; ++c)
        EXPECT_GE(doc["sh"]["minIrradiance"]["after"][c].get<double>(), 0.0);
    Ktx2Image k = readKtx2(cube);
    EXPECT_EQ(k.faceCount, 6u);
    EXPECT_EQ(k.pixelWidth, 8u);
    EXPECT_EQ(k.keyValues["iblbake.product"], "irradiance");
    EXPECT_EQ(k.keyValues["iblbake.irradianceNormalization"].rfind("E/pi", 0), 0u);
    EXPECT_EQ(entryCount(dir), 3u); // input, JSON, cube: no temporary left
    // The SH method and a fixed window.
    r = runCli("diffuse " + input.string() + " -o " + json.string() + " --irradiance-cube " + cube.string() +
               " --size 12 --irradiance-method sh --window sloan --window-param 0.02 --backend cpu");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::ifstream in2(json);
    doc = nlohmann::json::parse(in2);
    EXPECT_EQ(doc["sh"]["window"]["name"], "sloan");
    EXPECT_DOUBLE_EQ(doc["sh"]["window"]["parameter"].get<double>(), 0.02);
    EXPECT_EQ(readKtx2(cube).keyValues["iblbake.method"].rfind("sh:", 0), 0u);
    fs::remove_all(dir);
}

TEST(DiffuseCli, BadInputIsOneLineNonZeroAndNothingWritten) {
    fs::path dir = freshTempDir("diffuse_bad");
    std::ofstream(dir / "broken.hdr") << "#?RADIANCE\nthis is not an image\n";
    fs::path input = writeSyntheticLatLong(dir);
    const std::string out =
        " -o " + (dir / "out.json").string() + " --irradiance-cube " + (dir / "out.ktx2").string();
    for (std::string args :
         {"diffuse " + (dir / "missing.exr").string() + out, "diffuse " + (dir / "broken.hdr").string() + out,
          "diffuse " + input.string() + out + " --size 12",          // sampled cube needs 2^k
          "diffuse " + input.string() + out + " --window gaussian",  // not a window
          "diffuse " + input.string() + out + " --window-param 0.1", // param without a family
          "diffuse " + input.string() + out + " --window hanning --window-param -2",
          "diffuse " + input.string() + " -o " + (dir / "out.json").string() + " --irradiance-cube " +
              (dir / "no-such-dir" / "out.ktx2").string()}) {
        test::CliRun r = runCli(args + " --backend cpu");
        EXPECT_NE(r.exitCode, 0) << args;
        EXPECT_EQ(lineCount(r.err), 1) << args << ": " << r.err;
        EXPECT_EQ(r.err.rfind("iblbake: error:", 0), 0u) << r.err;
        EXPECT_FALSE(fs::exists(dir / "out.json")) << args;
        EXPECT_FALSE(fs::exists(dir / "out.ktx2")) << args;
        EXPECT_EQ(entryCount(dir), 2u) << args; // broken.hdr and sky.exr only
    }
    test::CliRun missing = runCli("diffuse " + (dir / "missing.exr").string() + out);
    EXPECT_NE(missing.err.find("missing.exr"), std::string::npos) << missing.err;
    fs::remove_all(dir);
}

} // namespace
