// Independent fp64 reference for the DFG / diffuse LUT: Frostbite 2014 Listing 18 written out again from
// the text (eq. 3 for G, NDF importance sampling, cosine sampling with frac(u + 0.5) for the Disney term),
// sharing no code with kernels/, so that a mistake in the kernels cannot hide in the reference. Used by
// tests/test_dfg.cpp and `iblbake accuracy`.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace ibl {

// (DFG1, DFG2, Disney diffuse) at one (NoV, perceptual roughness) with `sampleCount` Hammersley samples.
glm::dvec3 referenceDfg(double NoV, double perceptualRoughness, std::uint32_t sampleCount);

// The same at the texel centres of a size x size LUT (bakeDfgLut's layout: index y * size + x, x: NoV =
// (x + 0.5) / size, y: perceptual roughness = (y + 0.5) / size), split over texels with TBB.
std::vector<glm::dvec3> referenceDfgGrid(std::uint32_t size, std::uint32_t sampleCount);

} // namespace ibl
