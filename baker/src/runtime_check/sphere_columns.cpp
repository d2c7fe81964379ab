// The runtime module's measure on material spheres (sphere_columns.h).
#include "iblbake/baker/sphere_columns.h"

#include "iblbake/baker/dfg_lut.h"
#include "iblbake/baker/irradiance.h"
#include "iblbake/baker/sh.h"

#include <glm/geometric.hpp>

#include <cmath>

namespace ibl {

namespace {

const glm::vec3 kDielectricBase(0.8f, 0.55f, 0.35f);
const glm::vec3 kMetalBase(0.95f, 0.64f, 0.54f);

std::vector<ShadingPoint> spherePoints(float perceptualRoughness, int grid) {
    const glm::vec3 cameras[] = {glm::vec3(0, 0, 1), glm::normalize(glm::vec3(0.3f, 0.9f, 0.3f))};
    std::vector<ShadingPoint> points;
    for (float metallic : {0.0f, 1.0f})
        for (glm::vec3 c : cameras) {
            glm::vec3 right =
                glm::normalize(glm::cross(std::abs(c.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0), c));
            glm::vec3 up = glm::cross(c, right);
            for (int j = 0; j < grid; ++j)
                for (int i = 0; i < grid; ++i) {
                    float u = (i + 0.5f) / grid * 2 - 1, v = (j + 0.5f) / grid * 2 - 1;
                    float z2 = 1 - u * u - v * v;
                    if (z2 < 0.15f * 0.15f) continue;
                    glm::vec3 n = u * right + v * up + std::sqrt(z2) * c;
                    points.push_back(makeShadingPoint(n, n, c, metallic > 0 ? kMetalBase : kDielectricBase,
                                                      metallic, perceptualRoughness));
                }
        }
    return points;
}

} // namespace

SphereColumns sphereColumns(const std::vector<float>& perceptualRoughness, int grid) {
    SphereColumns c;
    for (float r : perceptualRoughness) {
        c.start.push_back(c.points.size());
        std::vector<ShadingPoint> column = spherePoints(r, grid);
        c.points.insert(c.points.end(), column.begin(), column.end());
    }
    c.start.push_back(c.points.size());
    return c;
}

std::vector<double> columnErrors(const SphereColumns& c, const ConvergedReference& reference,
                                 const std::vector<glm::vec4>* shaded) {
    std::vector<double> out;
    for (std::size_t k = 0; k + 1 < c.start.size(); ++k) {
        double err = 0.0, sum = 0.0;
        for (std::size_t i = c.start[k]; i < c.start[k + 1]; ++i) {
            const glm::dvec3 want = reference.results[i].total();
            for (int ch = 0; ch < 3; ++ch) {
                err +=
                    shaded ? std::abs(double((*shaded)[i][ch]) - want[ch]) : reference.errorEstimate[i][ch];
                sum += std::abs(want[ch]);
            }
        }
        out.push_back(sum > 0.0 ? err / sum : err);
    }
    return out;
}

ProbeSet shippedProbe(const CubeMap& probeSource, const CubeMap& full, const std::optional<SunDisk>& sun,
                      const SpecularSettings& settings, const DfgTable& dfg, const Executor& executor,
                      CubeMapChain* chainOut) {
    SpecularWithRoughLayers baked = bakeSpecularWithRoughLayers(probeSource, settings, executor);
    CubeMapChain& chain = baked.chain;
    const bool sunInLevel0 = sun && keepSunInLevel0(chain, full, Ktx2Format::RGBA32F);
    LdPyramid ld = ldPyramidFromChain(chain, MipMapping::Frostbite);
    ld.sunInLevel0 = sunInLevel0;
    ProbeSet set(std::move(ld), dfg, shCoefficientsFrom(bakeDiffuseSH(probeSource, {}).irradiance, false));
    set.setIrradianceCube(bakeIrradianceCube(probeSource, IrradianceSettings{}, executor));
    set.setRoughLayers(baked.roughLayers);
    if (sun) set.setSun(*sun);
    if (chainOut) *chainOut = std::move(chain);
    return set;
}

} // namespace ibl
