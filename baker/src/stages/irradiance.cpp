// The diffuse irradiance cube (iblbake/baker/irradiance.h): sampled (kernels/irradiance.h on OpenCL or TBB),
// from SH, and the brute-force reference.
#include "iblbake/baker/irradiance.h"
#include "iblbake/core/cube_pyramid.h"
#include "iblbake/core/error.h"
#include "iblbake/core/numeric.h"
#include "iblbake/opencl/dispatch.h"

#include "bright_split.h"

#include <irradiance.h>
#include <sh.h>

#include <tbb/parallel_for.h>

#include <cmath>
#include <cstddef>

namespace ibl {
namespace {

static_assert(sizeof(IrradianceParams) == sizeof(CubePyramidLayout) + 16 &&
                  offsetof(IrradianceParams, brightCount) == sizeof(CubePyramidLayout) + 12,
              "IrradianceParams must match irradiance.h");

std::vector<float> sampleTable(std::uint32_t n, int sourceFaceSize, float lodBias, float maxLod) {
    const float omegaP = 4.0f * IBL_PI / (6.0f * float(sourceFaceSize) * float(sourceFaceSize));
    std::vector<float> table;
    table.reserve(std::size_t(n) * IBL_IRRADIANCE_SAMPLE_FLOATS);
    for (std::uint32_t i = 0; i < n; ++i) {
        IrradianceSample s = irradianceSampleEntry(i, n, omegaP, lodBias, maxLod);
        table.insert(table.end(), {s.x, s.y, s.z, s.lod}); // IBL_IRRADIANCE_SAMPLE_FLOATS
    }
    return table;
}

vec3 texelDirection(int face, int x, int y, int n) {
    return glm::normalize(
        cubeFaceDirection(face, (float(x) + 0.5f) / float(n), (float(y) + 0.5f) / float(n)));
}

} // namespace

IrradianceMethod parseIrradianceMethod(const std::string& name) {
    if (name == "sampled") return IrradianceMethod::Sampled;
    if (name == "sh") return IrradianceMethod::SH;
    throw SettingError("irradianceMethod", "'" + name + "' is not one of sampled, sh");
}

const char* irradianceMethodName(IrradianceMethod method) {
    return method == IrradianceMethod::SH ? "sh" : "sampled";
}

std::uint32_t irradianceSamplesFor(const IrradianceSettings& s) {
    if (s.samples > 0) return s.samples;
    switch (s.quality) {
    case Quality::Draft:
        return 128;
    case Quality::Reference:
        return 4096;
    default:
        return 512;
    }
}

CubeMap bakeIrradianceCube(const CubeMap& source, const IrradianceSettings& settings,
                           const Executor& executor) {
    if (!isPowerOfTwo(source.faceSize) || source.faceSize > 8192)
        throw Error("irradiance: source face size " + std::to_string(source.faceSize) +
                    " is not a power of two up to 8192");
    if (settings.faceSize < 1 || settings.faceSize > 4096)
        throw SettingError("irradianceFaceSize",
                           "the face size " + std::to_string(settings.faceSize) + " is not from 1 to 4096");
    BrightSplit split = splitBrightTexels(source, settings.brightThreshold, settings.maxBrightTexels);
    CubePyramid pyramid = buildCubePyramid(split.residual);
    const std::uint32_t samples = irradianceSamplesFor(settings);
    std::vector<float> table =
        sampleTable(samples, source.faceSize, settings.lodBias, float(pyramid.layout.levelCount - 1));
    IrradianceParams params{pyramid.layout, std::uint32_t(settings.faceSize), samples, 1.0f / float(samples),
                            split.bright.count()};
    const Dispatcher dispatcher(executor);
    DispatchOutput cube = dispatcher.output(DispatchGrid::cube(params.faceSize));
    dispatcher.run(kernel("irradiance.cl", "irradianceSampled", irradianceSampledItem), cube, params,
                   dispatcher.share("irradiance source pyramid", pyramid.data),
                   dispatcher.upload("irradiance sample table", table));
    if (params.brightCount > 0)
        dispatcher.run(kernel("irradiance.cl", "irradianceBright", irradianceBrightItem), cube, params,
                       dispatcher.upload("bright texels", split.bright.entries));
    return dispatcher.downloadCube(cube);
}

CubeMap irradianceCubeFromSH(const ShRgb& prescaledIrradiance, int faceSize, std::uint64_t* clampedTexels) {
    if (faceSize < 1 || faceSize > 4096)
        throw SettingError("irradianceFaceSize",
                           "the face size " + std::to_string(faceSize) + " is not from 1 to 4096");
    // The kernel-side evaluation (kernels/sh.h) on the pre-scaled coefficients with the 1/pi folded in.
    std::array<float, 27> sh;
    for (int i = 0; i < 9; ++i)
        for (int c = 0; c < 3; ++c)
            sh[std::size_t(3 * i + c)] = float(prescaledIrradiance[std::size_t(i)][c] / kPi);
    CubeMap out(faceSize);
    std::uint64_t clamped = 0;
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < faceSize; ++y)
            for (int x = 0; x < faceSize; ++x) {
                vec3 e = shEvalPrescaled(sh.data(), texelDirection(f, x, y, faceSize));
                if (e.x < 0.0f || e.y < 0.0f || e.z < 0.0f) ++clamped;
                out.faces[std::size_t(f)].at(x, y) = glm::vec4(glm::max(e, vec3(0.0f)), 1.0f);
            }
    if (clampedTexels) *clampedTexels = clamped;
    return out;
}

CubeMap referenceIrradianceCube(const CubeMap& source, int faceSize) {
    const int w = source.faceSize;
    const std::size_t count = 6 * std::size_t(w) * std::size_t(w);
    struct Texel {
        glm::dvec3 direction;
        glm::dvec3 weighted; // L omega
    };
    std::vector<Texel> texels(count);
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < w; ++y)
            for (int x = 0; x < w; ++x)
                texels[(std::size_t(f) * w + y) * w + x] = {
                    glm::normalize(
                        glm::dvec3(cubeFaceDirection(f, (x + 0.5f) / float(w), (y + 0.5f) / float(w)))),
                    glm::dvec3(glm::vec3(source.faces[std::size_t(f)].at(x, y))) * texelSolidAngle(x, y, w)};
    const int n = faceSize;
    CubeMap out(n);
    tbb::parallel_for(0, 6 * n, [&](int row) {
        const int face = row / n, y = row % n;
        for (int x = 0; x < n; ++x) {
            glm::dvec3 nrm = glm::normalize(
                glm::dvec3(cubeFaceDirection(face, (x + 0.5f) / float(n), (y + 0.5f) / float(n))));
            glm::dvec3 sum(0.0);
            for (const Texel& t : texels)
                sum += std::max(0.0, glm::dot(nrm, t.direction)) * t.weighted;
            out.faces[std::size_t(face)].at(x, y) = glm::vec4(glm::vec3(sum / kPi), 1.0f);
        }
    });
    return out;
}

} // namespace ibl
