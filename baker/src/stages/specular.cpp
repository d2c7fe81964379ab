#include "iblbake/specular.h"
#include "iblbake/error.h"

#include <ld.h>

#include <tbb/parallel_for.h>

#include <chrono>
#include <cmath>

namespace ibl {
namespace {

static_assert(sizeof(CubePyramidLayout) == 4 * (1 + 2 * IBL_MAX_CUBE_LEVELS), "CubePyramidLayout must match");
static_assert(sizeof(LdParams) == sizeof(CubePyramidLayout) + 12 &&
                  offsetof(LdParams, invWeightSum) == sizeof(CubePyramidLayout) + 8,
              "LdParams must match ld.h");

struct LevelTable {
    std::vector<float> samples; // 5 floats each, all above the horizon
    float invWeightSum = 0.0f;
    std::uint32_t count() const { return std::uint32_t(samples.size() / 5); }
};

LevelTable levelTable(std::uint32_t n, float alpha, int sourceFaceSize, float lodBias, float maxLod) {
    const float omegaP = 4.0f * IBL_PI / (6.0f * float(sourceFaceSize) * float(sourceFaceSize));
    LevelTable t;
    double weightSum = 0.0;
    for (std::uint32_t i = 0; i < n; ++i) {
        LdSample s = ldSampleEntry(i, n, alpha, omegaP, lodBias, maxLod);
        if (s.weight <= 0.0f) continue; // below the horizon: contributes nothing (Listing 19's NdotL > 0)
        t.samples.insert(t.samples.end(), {s.x, s.y, s.z, s.weight, s.lod});
        weightSum += s.weight;
    }
    t.invWeightSum = weightSum > 0.0 ? float(1.0 / weightSum) : 0.0f;
    return t;
}

CubeMap levelCpu(const CubePyramid& pyramid, const LevelTable& table, int n) {
    CubeMap out(n);
    tbb::parallel_for(0, 6 * n, [&](int row) {
        int face = row / n, y = row % n;
        for (int x = 0; x < n; ++x) {
            vec3 d = glm::normalize(
                cubeFaceDirection(face, (float(x) + 0.5f) / float(n), (float(y) + 0.5f) / float(n)));
            vec3 c = integrateLd(d, pyramid.data.data(), pyramid.layout, table.samples.data(), table.count(),
                                 table.invWeightSum);
            out.faces[face].at(x, y) = glm::vec4(c, 1.0f);
        }
    });
    return out;
}

CubeMap levelOpenCL(ocl::Context& cl, const cl::Buffer& pyramidBuffer, const CubePyramid& pyramid,
                    const LevelTable& table, int n) {
    CubeMap out(n);
    cl::Kernel kernel = cl.kernel("ld.cl", "ldLevel");
    cl::Buffer tableBuffer = cl.upload(table.samples);
    const std::size_t faceTexels = std::size_t(n) * std::size_t(n);
    cl::Buffer outBuffer = cl.createBuffer(CL_MEM_WRITE_ONLY, 6 * faceTexels * sizeof(glm::vec4));
    LdParams params{pyramid.layout, std::uint32_t(n), table.count(), table.invWeightSum};
    kernel.setArg(0, params);
    kernel.setArg(1, pyramidBuffer);
    kernel.setArg(2, tableBuffer);
    kernel.setArg(3, outBuffer);
    // Groups of up to 16 adjacent texels of one row: same face, nearby fetches, uniform loop.
    const std::size_t groupWidth = std::min<std::size_t>(16, std::size_t(n));
    const std::size_t width = (std::size_t(n) + groupWidth - 1) / groupWidth * groupWidth;
    cl.run(kernel, cl::NDRange(width, std::size_t(n), 6), cl::NDRange(groupWidth, 1, 1));
    std::vector<glm::vec4> pixels(6 * faceTexels);
    cl.download(outBuffer, pixels.size() * sizeof(glm::vec4), pixels.data());
    for (int f = 0; f < 6; ++f)
        std::copy(pixels.begin() + f * faceTexels, pixels.begin() + (f + 1) * faceTexels,
                  out.faces[f].pixels.begin());
    return out;
}

bool isPowerOfTwo(int v) {
    return v > 0 && (v & (v - 1)) == 0;
}

} // namespace

MipMapping parseMipMapping(const std::string& name) {
    if (name == "frostbite") return MipMapping::Frostbite;
    if (name == "linear") return MipMapping::Linear;
    throw Error("--mip-mapping: '" + name + "' is not one of frostbite, linear");
}

const char* mipMappingName(MipMapping mapping) {
    return mapping == MipMapping::Linear ? "linear" : "frostbite";
}

float perceptualRoughnessForLevel(int level, int levelCount, MipMapping mapping) {
    if (levelCount <= 1) return 0.0f;
    float t = float(level) / float(levelCount - 1);
    return mapping == MipMapping::Linear ? t : t * t;
}

Quality parseQuality(const std::string& name) {
    if (name == "draft") return Quality::Draft;
    if (name == "production") return Quality::Production;
    if (name == "reference") return Quality::Reference;
    throw Error("--quality: '" + name + "' is not one of draft, production, reference");
}

const char* qualityName(Quality q) {
    return q == Quality::Draft ? "draft" : q == Quality::Reference ? "reference" : "production";
}

std::uint32_t samplesFor(const SpecularSettings& s) {
    if (s.samples > 0) return s.samples;
    switch (s.quality) {
    case Quality::Draft:
        return 32;
    case Quality::Reference:
        return 2048;
    default:
        return 256;
    }
}

int levelCountFor(int faceSize, const SpecularSettings& s) {
    int full = int(std::log2(double(faceSize))) + 1;
    return s.levels > 0 ? std::min(s.levels, full) : full;
}

CubeMapChain bakeSpecular(const CubeMap& source, const SpecularSettings& settings, const Executor& executor,
                          std::vector<SpecularLevelTiming>* timings) {
    if (!isPowerOfTwo(source.faceSize) || source.faceSize > 8192)
        throw Error("specular: face size " + std::to_string(source.faceSize) +
                    " is not a power of two up to 8192");
    const int levelCount = levelCountFor(source.faceSize, settings);
    const std::uint32_t samples = samplesFor(settings);
    CubePyramid pyramid = buildCubePyramid(source);
    const float maxLod = float(pyramid.layout.levelCount - 1);
    cl::Buffer pyramidBuffer;
    if (executor.usesOpenCL()) pyramidBuffer = executor.cl().upload(pyramid.data);

    CubeMapChain chain;
    chain.levels.push_back(source); // level 0: the mirror, unconvolved (Frostbite footnote 43)
    for (int m = 1; m < levelCount; ++m) {
        auto start = std::chrono::steady_clock::now();
        float r = perceptualRoughnessForLevel(m, levelCount, settings.mapping);
        LevelTable table =
            levelTable(samples, alphaFromPerceptual(r), source.faceSize, settings.lodBias, maxLod);
        int n = std::max(1, source.faceSize >> m);
        chain.levels.push_back(executor.usesOpenCL()
                                   ? levelOpenCL(executor.cl(), pyramidBuffer, pyramid, table, n)
                                   : levelCpu(pyramid, table, n));
        if (timings)
            timings->push_back(
                {m, r,
                 std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                     .count()});
    }
    return chain;
}

CubeMap referenceSpecularLevel(const CubeMap& source, int outputFaceSize, float perceptualRoughness) {
    const int w = source.faceSize, n = outputFaceSize;
    const double alpha = double(perceptualRoughness) * perceptualRoughness;
    std::vector<glm::dvec3> dirs(6 * std::size_t(w) * w);
    std::vector<double> solidAngles(dirs.size());
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < w; ++y)
            for (int x = 0; x < w; ++x) {
                std::size_t k = (std::size_t(f) * w + y) * w + x;
                dirs[k] = glm::normalize(glm::dvec3(cubeFaceDirection(f, (x + 0.5f) / w, (y + 0.5f) / w)));
                solidAngles[k] = cubeTexelSolidAngle(x, y, w);
            }
    CubeMap out(n);
    tbb::parallel_for(0, 6 * n, [&](int row) {
        int face = row / n, y = row % n;
        for (int x = 0; x < n; ++x) {
            glm::dvec3 nrm =
                glm::normalize(glm::dvec3(cubeFaceDirection(face, (x + 0.5f) / n, (y + 0.5f) / n)));
            glm::dvec3 sum(0.0);
            double weightSum = 0.0;
            for (std::size_t k = 0; k < dirs.size(); ++k) {
                double NoL = glm::dot(nrm, dirs[k]);
                if (NoL <= 0.0) continue;
                // Expectation of Listing 19's estimator: samples l with pdf D(h) / 4 (N = V), weighted by
                // NoL.
                double NoH = glm::dot(nrm, glm::normalize(nrm + dirs[k]));
                double a2 = alpha * alpha, d = NoH * NoH * (a2 - 1.0) + 1.0;
                double weight = a2 / (d * d) * NoL * solidAngles[k];
                const glm::vec4& c = source.faces[k / (std::size_t(w) * w)].pixels[k % (std::size_t(w) * w)];
                sum += weight * glm::dvec3(c);
                weightSum += weight;
            }
            out.faces[face].at(x, y) = glm::vec4(glm::vec3(sum / weightSum), 1.0f);
        }
    });
    return out;
}

} // namespace ibl
