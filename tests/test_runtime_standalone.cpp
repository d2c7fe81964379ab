// The runtime module linked on its own (iblbake_runtime only: no baker, no OpenImageIO/OpenColorIO): a probe
// set built from in-memory data, evaluated on the CPU and through OpenCL, and the reference renderer's own
// white furnace.
#include <iblbake/core/error.h>
#include <iblbake/opencl/executor.h>
#include <iblbake/runtime/runtime.h>
#include <iblbake/runtime/runtime_reference.h>

#include <dfg.h>

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

namespace {

using namespace ibl;

CubeMap constantCube(int n, glm::vec3 c) {
    CubeMap cube(n);
    for (ImageRGBA& f : cube.faces)
        for (glm::vec4& p : f.pixels)
            p = glm::vec4(c, 1.0f);
    return cube;
}

// A small DFG LUT straight from kernels/dfg.h (what the baker's stage integrates).
ImageRGBA smallDfgLut(uint32_t size, uint32_t samples) {
    std::vector<float> table(4 * std::size_t(samples));
    for (uint32_t i = 0; i < samples; ++i) {
        float4 e = dfgSampleEntry(i, samples);
        for (int c = 0; c < 4; ++c)
            table[4 * i + c] = e[c];
    }
    ImageRGBA lut{int(size), int(size)};
    for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x) {
            vec3 s =
                integrateDfgChunk(dfgTexelCenter(x, size), dfgTexelCenter(y, size), table.data(), 0, samples);
            lut.at(int(x), int(y)) = glm::vec4(s / float(samples), 1.0f);
        }
    return lut;
}

TEST(RuntimeStandalone, ConstantEnvironmentCpuOpenCLAndReference) {
    const glm::vec3 L(0.5f, 1.0f, 2.0f);
    CubeMapChain chain;
    for (int n = 16; n >= 1; n /= 2)
        chain.levels.push_back(constantCube(n, L));
    ShCoefficients sh;
    sh.c[0] = L * 3.14159265f; // E(n) = pi L everywhere
    ProbeSet set(ldPyramidFromChain(chain), dfgTableFromImage(smallDfgLut(32, 512)), sh);

    std::vector<ShadingPoint> points;
    for (float r : {0.0f, 0.25f, 0.5f, 0.75f, 1.0f})
        for (float m : {0.0f, 1.0f})
            points.push_back(makeShadingPoint(glm::vec3(0), glm::vec3(0, 1, 0),
                                              glm::normalize(glm::vec3(0.3f, 1, 0)), glm::vec3(1.0f), m, r));
    RuntimeOptions options;
    std::vector<glm::vec4> cpu = evaluateCpu(set, points, options);
    std::vector<ReferenceResult> ref = renderReference(ReferenceLighting::distant(constantCube(8, L)), points,
                                                       options, {.samplesPerStrategy = 512});
    for (std::size_t i = 0; i < points.size(); ++i) {
        glm::dvec3 reference = ref[i].total();
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(cpu[i][c], reference[c], 0.02 * reference[c]) << i;
            // Metal, f0 = 1, energy compensation: the furnace returns the environment (runtime and
            // reference).
            if (points[i].metallic == 1.0f) {
                EXPECT_NEAR(cpu[i][c], L[c], 0.02f * L[c]);
                EXPECT_NEAR(reference[c], L[c], 0.005 * L[c]);
            }
        }
    }

    std::ostringstream warnings;
    Executor executor = Executor::create(Backend::Auto, "", warnings);
    if (!executor.usesOpenCL()) GTEST_SKIP() << "no OpenCL device";
    OpenCLProbeEvaluator cl(executor.cl(), set);
    std::vector<glm::vec4> gpu = cl.evaluate(points, options);
    for (std::size_t i = 0; i < points.size(); ++i)
        for (int c = 0; c < 4; ++c)
            EXPECT_NEAR(gpu[i][c], cpu[i][c], 1e-4f * std::max(1.0f, std::abs(cpu[i][c])));
}

TEST(RuntimeStandalone, RejectsInconsistentData) {
    EXPECT_THROW(ldPyramidFromChain(CubeMapChain{}), Error);
    CubeMapChain notPowerOfTwo{{CubeMap(12)}};
    EXPECT_THROW(ldPyramidFromChain(notPowerOfTwo), Error);
    EXPECT_THROW(dfgTableFromImage(ImageRGBA(4, 8)), Error);
    EXPECT_THROW(ProbeSet(LdPyramid{}, DfgTable{}, ShCoefficients{}), Error);
}

} // namespace
