#include "iblbake/baker/dfg_reference.h"

#include <tbb/parallel_for.h>

#include <cmath>

#include <glm/geometric.hpp>

namespace ibl {

glm::dvec3 referenceDfg(double NoV, double perceptualRoughness, std::uint32_t sampleCount) {
    const double pi = 3.14159265358979323846;
    double alpha = perceptualRoughness * perceptualRoughness;
    double vx = std::sqrt(1.0 - NoV * NoV), vz = NoV;
    auto lambda = [&](double c) {
        return (-1.0 + std::sqrt(1.0 + alpha * alpha * (1.0 - c * c) / (c * c))) / 2.0;
    };
    auto schlick = [](double f0, double f90, double u) { return f0 + (f90 - f0) * std::pow(1.0 - u, 5.0); };
    glm::dvec3 acc(0.0);
    for (std::uint32_t i = 0; i < sampleCount; ++i) {
        std::uint32_t bits = i;
        bits = (bits << 16u) | (bits >> 16u);
        bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
        bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
        bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
        bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
        double u1 = double(i) / sampleCount, u2 = double(bits) / 4294967296.0;

        double cosT = std::sqrt((1.0 - u1) / (1.0 + (alpha * alpha - 1.0) * u1));
        double sinT = std::sqrt(1.0 - cosT * cosT), phi = 2.0 * pi * u2;
        glm::dvec3 h(sinT * std::cos(phi), sinT * std::sin(phi), cosT);
        double VoH = vx * h.x + vz * h.z;
        glm::dvec3 l = 2.0 * VoH * h - glm::dvec3(vx, 0.0, vz);
        if (l.z > 0.0 && VoH > 0.0) {
            double G = 1.0 / (1.0 + lambda(NoV) + lambda(l.z));
            double GVis = G * VoH / (h.z * NoV);
            double Fc = std::pow(1.0 - VoH, 5.0);
            acc.x += (1.0 - Fc) * GVis;
            acc.y += Fc * GVis;
        }
        double w1 = std::fmod(u1 + 0.5, 1.0), w2 = std::fmod(u2 + 0.5, 1.0);
        double r = std::sqrt(w1), phid = 2.0 * pi * w2;
        glm::dvec3 ld(r * std::cos(phid), r * std::sin(phid), std::sqrt(1.0 - w1));
        glm::dvec3 hd = glm::normalize(ld + glm::dvec3(vx, 0.0, vz));
        double LoH = glm::dot(ld, hd);
        double energyBias = 0.5 * perceptualRoughness,
               energyFactor = 1.0 + (1.0 / 1.51 - 1.0) * perceptualRoughness;
        double fd90 = energyBias + 2.0 * LoH * LoH * perceptualRoughness;
        acc.z += schlick(1.0, fd90, ld.z) * schlick(1.0, fd90, NoV) * energyFactor;
    }
    return acc / double(sampleCount);
}

std::vector<glm::dvec3> referenceDfgGrid(std::uint32_t size, std::uint32_t sampleCount) {
    std::vector<glm::dvec3> grid(std::size_t(size) * size);
    tbb::parallel_for(std::uint32_t(0), size * size, [&](std::uint32_t k) {
        grid[k] = referenceDfg((k % size + 0.5) / size, (k / size + 0.5) / size, sampleCount);
    });
    return grid;
}

} // namespace ibl
