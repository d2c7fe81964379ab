// Rough layers (kernels/mip_mapping.h IBL_ROUGH_LAYER_*): a fixed-size cube array on a fine roughness grid
// that takes over from the chain's coarse levels. Analytic cases, the blend's continuity, OpenCL against the
// CPU, bad inputs, and lookups on the shared HDRIs against the exact LD (issue 14, "coarse levels").
#include "cli_runner.h"
#include "runtime_test_support.h"
#include "test_support.h"

#include <iblbake/baker/products.h>
#include <iblbake/core/error.h>
#include <iblbake/ktx2/cube_profile.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

namespace {

using namespace ibl;

// Layer k of constant colour (k + 1, 2 (k + 1), 1) on faces of n texels.
std::vector<CubeMap> constantLayers(int n) {
    std::vector<CubeMap> layers;
    for (std::uint32_t k = 0; k < IBL_ROUGH_LAYER_COUNT; ++k)
        layers.push_back(
            rt_test::makeCube(n, [k](glm::vec3) { return glm::vec3(k + 1.0f, 2.0f * (k + 1), 1.0f); }));
    return layers;
}

TEST(RoughLayers, GridIsTheFrostbiteMappingOnTwentyOneLevels) {
    EXPECT_FLOAT_EQ(roughLayerRoughness(0), 0.2025f);
    EXPECT_FLOAT_EQ(roughLayerRoughness(IBL_ROUGH_LAYER_COUNT - 1), 1.0f);
    for (std::uint32_t k = 0; k < IBL_ROUGH_LAYER_COUNT; ++k) {
        EXPECT_FLOAT_EQ(roughLayerRoughness(k),
                        perceptualRoughnessForLevel(int(IBL_ROUGH_LAYER_FIRST + k),
                                                    int(IBL_ROUGH_LAYER_GRID) + 1, MipMapping::Frostbite));
        EXPECT_NEAR(roughLayerForRoughness(roughLayerRoughness(k)), float(k), 1e-5f);
    }
    EXPECT_EQ(roughLayerWeight(0.0f), 0.0f);
    EXPECT_EQ(roughLayerWeight(roughLayerRoughness(0)), 0.0f);
    EXPECT_EQ(roughLayerWeight(roughLayerRoughness(1)), 1.0f);
    EXPECT_EQ(roughLayerWeight(1.0f), 1.0f);
    EXPECT_EQ(roughLayerFaceSize(256), 32u);
    EXPECT_EQ(roughLayerFaceSize(8), 8u);
    EXPECT_EQ(roughLayerFaceSize(1), 1u);
}

// A constant environment: every layer is the constant at every texel (white furnace), on both backends and
// at face sizes down to one texel.
TEST(RoughLayers, WhiteFurnaceEveryLayerEveryTexel) {
    for (int n : {1, 2, 16, 64})
        for (const Executor& executor : {Executor::cpu(), rt_test::openclOrCpu()}) {
            const CubeMap constant = rt_test::makeCube(n, [](glm::vec3) { return glm::vec3(0.75f); });
            const std::vector<CubeMap> layers = bakeRoughLayers(constant, SpecularSettings{}, executor);
            ASSERT_EQ(layers.size(), IBL_ROUGH_LAYER_COUNT);
            for (const CubeMap& layer : layers) {
                ASSERT_EQ(layer.faceSize, std::min(n, 32));
                for (const ImageRGBA& face : layer.faces)
                    for (const glm::vec4& p : face.pixels)
                        for (int c = 0; c < 3; ++c)
                            ASSERT_NEAR(p[c], 0.75f, 0.75f * 1e-4f) << n << " " << executor.description();
            }
        }
}

// A one-texel sun 10^6 times the sky: every layer finite, non-negative, and holding the source's energy
// (sum of RGB x solid angle) within 1%, on both backends (the bright texel is integrated exactly: ld.h).
TEST(RoughLayers, SunAMillionTimesTheSkyKeepsEachLayersEnergy) {
    CubeMap source = rt_test::makeCube(64, [](glm::vec3) { return glm::vec3(1.0f); });
    source.faces[2].at(20, 41) = glm::vec4(1e6f, 9e5f, 8e5f, 1.0f);
    const auto energy = [](const CubeMap& cube) {
        double sum = 0.0;
        for (int f = 0; f < 6; ++f)
            for (int y = 0; y < cube.faceSize; ++y)
                for (int x = 0; x < cube.faceSize; ++x) {
                    const glm::vec4 p = cube.faces[f].at(x, y);
                    sum += (double(p.x) + p.y + p.z) * cubeTexelSolidAngle(x, y, cube.faceSize);
                }
        return sum;
    };
    const double sourceEnergy = energy(source);
    for (const Executor& executor : {Executor::cpu(), rt_test::openclOrCpu()}) {
        const std::vector<CubeMap> layers = bakeRoughLayers(source, SpecularSettings{}, executor);
        double worst = 0.0;
        for (std::size_t k = 0; k < layers.size(); ++k) {
            worst = std::max(worst, std::abs(energy(layers[k]) / sourceEnergy - 1.0));
            for (const ImageRGBA& face : layers[k].faces)
                for (const glm::vec4& p : face.pixels)
                    for (int c = 0; c < 3; ++c)
                        ASSERT_TRUE(std::isfinite(p[c]) && p[c] >= 0.0f) << k;
            EXPECT_NEAR(energy(layers[k]) / sourceEnergy, 1.0, 0.01) << k << " " << executor.description();
        }
        std::printf("%s: worst layer energy off by %.4f%%\n", executor.description().c_str(), 100.0 * worst);
    }
}

// One bake of the chain and its layers gives the bits of the two separate bakes, on both backends.
TEST(RoughLayers, BakedWithTheChainTheyAreTheSameBits) {
    const CubeMap source = rt_test::makeCube(64, rt_test::skyLike);
    for (const Executor& executor : {Executor::cpu(), rt_test::openclOrCpu()}) {
        const SpecularWithRoughLayers both =
            bakeSpecularWithRoughLayers(source, SpecularSettings{}, executor);
        const CubeMapChain chain = bakeSpecular(source, SpecularSettings{}, executor);
        const std::vector<CubeMap> layers = bakeRoughLayers(source, SpecularSettings{}, executor);
        ASSERT_EQ(both.chain.levels.size(), chain.levels.size());
        for (std::size_t m = 0; m < chain.levels.size(); ++m)
            for (int f = 0; f < 6; ++f)
                EXPECT_EQ(both.chain.levels[m].faces[f].pixels, chain.levels[m].faces[f].pixels) << m;
        ASSERT_EQ(both.roughLayers.size(), layers.size());
        for (std::size_t k = 0; k < layers.size(); ++k)
            for (int f = 0; f < 6; ++f)
                EXPECT_EQ(both.roughLayers[k].faces[f].pixels, layers[k].faces[f].pixels) << k;
    }
}

TEST(RoughLayers, OpenCLBakeAgreesWithCpu) {
    const Executor cl = rt_test::openclOrCpu();
    if (!cl.usesOpenCL()) GTEST_SKIP() << "no OpenCL device";
    const CubeMap source = rt_test::makeCube(64, rt_test::skyLike);
    const std::vector<CubeMap> a = bakeRoughLayers(source, SpecularSettings{}, Executor::cpu());
    const std::vector<CubeMap> b = bakeRoughLayers(source, SpecularSettings{}, cl);
    for (std::size_t k = 0; k < a.size(); ++k)
        EXPECT_LT(ibl::test::relativeMeanAbsError(b[k], a[k]), 1e-5) << k;
}

// The lookup: the chain alone (the same bits) up to r_0 and without layers, the layers alone from r_1 on
// (exactly layer k at r_k), a blend between that is continuous at both ends.
TEST(RoughLayers, LookupIsTheChainBelowTheLayersAboveAndContinuous) {
    const CubeMap source = rt_test::makeCube(64, rt_test::skyLike);
    ProbeSet set(rt_test::bakeLd(source), dfgTableFromImage(rt_test::dfgLut()), ShCoefficients{});
    const RuntimeParams without = makeRuntimeParams(set, {}, 1);
    EXPECT_EQ(without.distantRoughLayers.layerCount, 0u);
    set.setRoughLayers(constantLayers(32));
    const RuntimeParams with = makeRuntimeParams(set, {}, 1);
    ASSERT_EQ(with.distantRoughLayers.layerCount, IBL_ROUGH_LAYER_COUNT);
    ASSERT_EQ(with.distantRoughLayers.faceSize, 32u);
    const float* data = set.distantData().data();
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int i = 0; i < 200; ++i) {
        const glm::vec3 d(u(rng), u(rng), u(rng) + 0.01f);
        for (float r : {0.0f, 0.1f, 0.2f, roughLayerRoughness(0)}) {
            const glm::vec3 chain = sampleLd(data, with.distant, d, r);
            EXPECT_EQ(sampleLdWithLayers(data, with.distant, with.distantRoughLayers, d, r), chain) << r;
            EXPECT_EQ(sampleLdWithLayers(data, without.distant, without.distantRoughLayers, d, r), chain);
        }
        for (std::uint32_t k = 1; k < IBL_ROUGH_LAYER_COUNT; ++k) {
            const glm::vec3 got =
                sampleLdWithLayers(data, with.distant, with.distantRoughLayers, d, roughLayerRoughness(k));
            EXPECT_NEAR(got.x, k + 1.0f, 1e-4f * (k + 1)) << k;
            EXPECT_NEAR(got.y, 2.0f * (k + 1), 2e-4f * (k + 1)) << k;
        }
        // Across the blend (r_0 to r_1) and the first layer interval, steps of 1e-4 in r move the result
        // by far less than the gaps it bridges (chain ~0.1-1 to the layers' 2 and 4 in green): no jump.
        for (float r = roughLayerRoughness(0); r < roughLayerRoughness(2); r += 1e-4f) {
            const glm::vec3 a = sampleLdWithLayers(data, with.distant, with.distantRoughLayers, d, r);
            const glm::vec3 b = sampleLdWithLayers(data, with.distant, with.distantRoughLayers, d, r + 1e-4f);
            ASSERT_LT(std::abs(b.y - a.y), 0.1f) << r;
        }
    }
    // Below r_0 a set with layers shades exactly as the same set without.
    ProbeSet plain(rt_test::bakeLd(source), dfgTableFromImage(rt_test::dfgLut()), ShCoefficients{});
    const std::vector<ShadingPoint> points = {
        makeShadingPoint({0, 0, 0}, {0, 1, 0}, {0.3f, 1, 0}, {1, 1, 1}, 1, 0.1f),
        makeShadingPoint({0, 0, 0}, {0, 1, 0}, {0.3f, 1, 0}, {1, 1, 1}, 1, 0.15f)};
    EXPECT_EQ(evaluateCpu(plain, points), evaluateCpu(set, points));
}

TEST(RoughLayers, WrongCountOrFaceSizeIsRefusedAndChangesNothing) {
    const CubeMap source = rt_test::makeCube(64, rt_test::skyLike);
    ProbeSet set(rt_test::bakeLd(source), dfgTableFromImage(rt_test::dfgLut()), ShCoefficients{});
    const std::vector<float> before = set.distantData();
    std::vector<CubeMap> tooFew = constantLayers(32);
    tooFew.pop_back();
    EXPECT_THROW(set.setRoughLayers(tooFew), Error);
    EXPECT_THROW(set.setRoughLayers(constantLayers(16)), Error); // the 64-px chain's layers have 32-px faces
    EXPECT_THROW(set.setRoughLayers({}), Error);
    EXPECT_EQ(set.roughLayers().layerCount, 0u);
    EXPECT_EQ(set.distantData(), before);
}

// OpenCL against the CPU runtime with layers, an irradiance cube and the sun in level 0 (the distant
// buffer's three parts), at roughness 0 to 1.
TEST(RoughLayers, OpenCLRuntimeAgreesWithCpu) {
    const CubeMap source = rt_test::makeCube(64, rt_test::skyLike);
    SunDisk sun{};
    sun.direction = glm::normalize(glm::vec3(0.3f, 0.8f, 0.2f));
    sun.angularRadius = 0.01f;
    sun.color = glm::vec3(1.0f);
    sun.illuminance = 1000.0f;
    ProbeSet set = rt_test::distantSetWithSun(source, source, sun);
    set.setRoughLayers(bakeRoughLayers(source, SpecularSettings{}, Executor::cpu()));
    std::vector<ShadingPoint> points;
    for (int i = 0; i <= 100; ++i) {
        const float a = 0.37f * float(i);
        points.push_back(makeShadingPoint({0, 0, 0}, {std::sin(a), 1.0f, std::cos(a)}, {0.2f, 1.0f, -0.4f},
                                          {0.9f, 0.6f, 0.4f}, float(i % 2), float(i) / 100.0f));
    }
    const double difference = rt_test::backendDifference(set, points, RuntimeOptions{});
    if (difference < 0.0) GTEST_SKIP() << "no OpenCL device";
    EXPECT_LT(difference, rt_test::kBackendTolerance);
}

// The product file (a scene bake's specular_rough.ktx2): written with a storage scale and either cube
// profile, read back by the runtime's loader as the layers it was given; a file of another grid, another
// layer count or no grid key is refused with its name.
TEST(RoughLayers, FilesRoundTripAndForeignOnesAreRefused) {
    const std::filesystem::path dir = ibl::test::freshTempDir("rough_layer_files");
    const CubeMap source = rt_test::makeCube(64, rt_test::skyLike);
    const std::vector<CubeMap> layers = bakeRoughLayers(source, SpecularSettings{}, Executor::cpu());
    Ktx2KeyValues keys = roughLayerKeyValues(LdChainProduct{}, CalibrationRecord{}, std::nullopt);
    for (const char* profile : {"standard", "three"}) {
        ProductStorage storage;
        storage.scale = 0.25;
        Ktx2KeyValues withProfile = keys;
        withProfile.emplace_back(kCubeProfileKey, profile);
        const std::filesystem::path file = dir / (std::string(profile) + ".ktx2");
        writeProductCubeArray(file, layers, Ktx2Format::RGBA32F, withProfile, storage);
        const std::vector<CubeMap> loaded = loadRoughLayersKtx2(file);
        ASSERT_EQ(loaded.size(), layers.size());
        for (std::size_t k = 0; k < layers.size(); ++k)
            for (int f = 0; f < 6; ++f)
                EXPECT_EQ(loaded[k].faces[f].pixels, layers[k].faces[f].pixels)
                    << profile << " " << k << " " << f;
    }
    const auto refused = [&](const std::string& name, const Ktx2KeyValues& kv, std::vector<CubeMap> cubes,
                             const std::string& cause) {
        const std::filesystem::path file = dir / name;
        writeKtx2CubeArray(file, cubes, Ktx2Format::RGBA16F, kv);
        try {
            loadRoughLayersKtx2(file);
            ADD_FAILURE() << name << " was read";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(cause), std::string::npos) << e.what();
        }
    };
    Ktx2KeyValues otherGrid = keys;
    for (auto& [key, value] : otherGrid)
        if (key == kRoughLayerRoughnessKey) value = "0.4 0.5 0.6 0.7 0.8 0.9 1 1 1 1 1 1";
    refused("other_grid.ktx2", otherGrid, layers, "another grid");
    refused("no_grid.ktx2", {{"iblbake.product", kRoughLayerProduct}}, layers, "is missing");
    refused("eleven.ktx2", keys, std::vector<CubeMap>(layers.begin(), layers.end() - 1), "11 layers");
    std::filesystem::remove_all(dir);
}

// The shared HDRIs at production (256-px faces, sun in the map): lookups through the layers against the
// exact LD (referenceSpecularTexels) at 512 texel centres of a 256-px face, beside the chain's trilinear
// lookup. Within 3% from r = 0.25 on (issue 14 asks r >= 0.6); up to r_0 the same bits as the chain.
class RoughLayersOnHdri : public ibl::test::SharedHdriTest {};

TEST_P(RoughLayersOnHdri, LookupsHoldTheExactLd) {
    const int size = 256;
    const CubeMap source = ibl::test::loadSharedHdri(GetParam(), size);
    const Executor executor = rt_test::openclOrCpu();
    ProbeSet set(ldPyramidFromChain(bakeSpecular(source, SpecularSettings{}, executor)),
                 dfgTableFromImage(rt_test::dfgLut()), ShCoefficients{});
    set.setRoughLayers(bakeRoughLayers(source, SpecularSettings{}, executor));
    const RuntimeParams p = makeRuntimeParams(set, {}, 1);
    std::mt19937 rng(7);
    std::vector<CubeTexel> texels;
    for (int i = 0; i < 512; ++i)
        texels.push_back({int(rng() % 6), int(rng() % size), int(rng() % size)});
    std::printf("%-26s r: chain / layers / reference estimate (%%)\n", GetParam());
    for (float r : {0.1f, 0.2f, 0.25f, 0.3f, 0.4f, 0.5f, 0.6f, 0.7f, 0.8f, 0.9f, 1.0f}) {
        const LdTexelReference reference = referenceSpecularTexels(source, size, r, texels);
        double sum = 0.0, chainError = 0.0, layersError = 0.0, estimate = 0.0;
        for (std::size_t i = 0; i < texels.size(); ++i) {
            const glm::vec3 d = cubeTexelDirection(texels[i].face, std::uint32_t(texels[i].x),
                                                   std::uint32_t(texels[i].y), std::uint32_t(size));
            const glm::vec3 chain = sampleLd(set.distantData().data(), p.distant, d, r);
            const glm::vec3 layers =
                sampleLdWithLayers(set.distantData().data(), p.distant, p.distantRoughLayers, d, r);
            if (r <= roughLayerRoughness(0)) {
                ASSERT_EQ(layers, chain) << r;
            }
            for (int c = 0; c < 3; ++c) {
                sum += reference.value[i][c];
                chainError += std::abs(chain[c] - reference.value[i][c]);
                layersError += std::abs(layers[c] - reference.value[i][c]);
                estimate += reference.errorEstimate[i][c];
            }
        }
        std::printf("  r %.2f: %6.2f / %5.2f / %4.2f\n", r, 100.0 * chainError / sum,
                    100.0 * layersError / sum, 100.0 * estimate / sum);
        if (r >= 0.25f) {
            EXPECT_LT(layersError / sum, 0.03) << GetParam() << " r " << r;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(SharedHdris, RoughLayersOnHdri, ::testing::ValuesIn(ibl::test::kSharedHdris),
                         ibl::test::hdriTestName);

} // namespace
