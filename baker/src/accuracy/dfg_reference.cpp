#include "iblbake/baker/dfg_reference.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace ibl {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Samples are taken in blocks whose directions (below) stay in the cache while every NoV of a row uses them.
constexpr std::uint32_t kBlock = 2048;

// (1 - u)^5 of the Schlick terms by multiplication: std::pow was a sixth of a sample's time.
double pow5(double x) {
    return (x * x) * (x * x) * x;
}

// Sample i's directions, which depend on the sample index and alpha only, not on NoV: the NDF-sampled half
// vector (Listing 18's importance sampling) and the cosine-sampled light direction of the Disney term (with
// frac(u + 0.5)). Computed once per row of the LUT and shared by its NoVs.
struct SampleDirections {
    glm::dvec3 half, diffuseLight;
};

SampleDirections sampleDirections(std::uint32_t i, std::uint32_t sampleCount, double alpha) {
    std::uint32_t bits = i;
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    double u1 = double(i) / sampleCount, u2 = double(bits) / 4294967296.0;

    double cosT = std::sqrt((1.0 - u1) / (1.0 + (alpha * alpha - 1.0) * u1));
    double sinT = std::sqrt(1.0 - cosT * cosT), phi = 2.0 * kPi * u2;
    double w1 = std::fmod(u1 + 0.5, 1.0), w2 = std::fmod(u2 + 0.5, 1.0);
    double r = std::sqrt(w1), phid = 2.0 * kPi * w2;
    return {glm::dvec3(sinT * std::cos(phi), sinT * std::sin(phi), cosT),
            glm::dvec3(r * std::cos(phid), r * std::sin(phid), std::sqrt(1.0 - w1))};
}

// The sums of (DFG1, DFG2, Disney diffuse) over samples[0, count) at one NoV, added to acc in sample order.
void accumulate(double NoV, double perceptualRoughness, const SampleDirections* samples, std::uint32_t count,
                glm::dvec3& acc) {
    double alpha = perceptualRoughness * perceptualRoughness;
    double vx = std::sqrt(1.0 - NoV * NoV), vz = NoV;
    auto lambda = [&](double c) {
        return (-1.0 + std::sqrt(1.0 + alpha * alpha * (1.0 - c * c) / (c * c))) / 2.0;
    };
    auto schlick = [](double f0, double f90, double u) { return f0 + (f90 - f0) * pow5(1.0 - u); };
    const double lambdaV = lambda(NoV);
    for (std::uint32_t i = 0; i < count; ++i) {
        const glm::dvec3& h = samples[i].half;
        double VoH = vx * h.x + vz * h.z;
        glm::dvec3 l = 2.0 * VoH * h - glm::dvec3(vx, 0.0, vz);
        if (l.z > 0.0 && VoH > 0.0) {
            double G = 1.0 / (1.0 + lambdaV + lambda(l.z));
            double GVis = G * VoH / (h.z * NoV);
            double Fc = pow5(1.0 - VoH);
            acc.x += (1.0 - Fc) * GVis;
            acc.y += Fc * GVis;
        }
        const glm::dvec3& ld = samples[i].diffuseLight;
        glm::dvec3 hd = glm::normalize(ld + glm::dvec3(vx, 0.0, vz));
        double LoH = glm::dot(ld, hd);
        double energyBias = 0.5 * perceptualRoughness,
               energyFactor = 1.0 + (1.0 / 1.51 - 1.0) * perceptualRoughness;
        double fd90 = energyBias + 2.0 * LoH * LoH * perceptualRoughness;
        acc.z += schlick(1.0, fd90, ld.z) * schlick(1.0, fd90, NoV) * energyFactor;
    }
}

// The reference at every NoV of `NoVs` for one perceptual roughness.
std::vector<glm::dvec3> referenceDfgRow(const std::vector<double>& NoVs, double perceptualRoughness,
                                        std::uint32_t sampleCount) {
    const double alpha = perceptualRoughness * perceptualRoughness;
    std::vector<glm::dvec3> acc(NoVs.size(), glm::dvec3(0.0));
    std::vector<SampleDirections> block(std::min(kBlock, sampleCount));
    for (std::uint32_t begin = 0; begin < sampleCount; begin += kBlock) {
        const std::uint32_t count = std::min(kBlock, sampleCount - begin);
        for (std::uint32_t i = 0; i < count; ++i)
            block[i] = sampleDirections(begin + i, sampleCount, alpha);
        for (std::size_t k = 0; k < NoVs.size(); ++k)
            accumulate(NoVs[k], perceptualRoughness, block.data(), count, acc[k]);
    }
    for (glm::dvec3& a : acc)
        a /= double(sampleCount);
    return acc;
}

} // namespace

glm::dvec3 referenceDfg(double NoV, double perceptualRoughness, std::uint32_t sampleCount) {
    return referenceDfgRow({NoV}, perceptualRoughness, sampleCount)[0];
}

std::vector<glm::dvec3> referenceDfgGrid(std::uint32_t size, std::uint32_t sampleCount) {
    std::vector<glm::dvec3> grid(std::size_t(size) * size);
    std::vector<double> NoVs(size);
    for (std::uint32_t x = 0; x < size; ++x)
        NoVs[x] = (x + 0.5) / size;
    tbb::parallel_for(std::uint32_t(0), size, [&](std::uint32_t y) {
        const std::vector<glm::dvec3> row = referenceDfgRow(NoVs, (y + 0.5) / size, sampleCount);
        std::copy(row.begin(), row.end(), grid.begin() + std::ptrdiff_t(y) * size);
    });
    return grid;
}

} // namespace ibl
