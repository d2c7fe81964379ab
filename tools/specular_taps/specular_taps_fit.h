// The offline fit of the runtime's multi-tap specular lookup (kernels/specular_taps_table.h, read by
// kernels/probe.h specularTaps): for each (NoV, r) of a grid, K taps of the LD chain in the plane of
// incidence, each with a direction (normalize(lerp(N, R, t))), a lookup roughness and a weight, whose sum
// best matches the normalized lobe the view sees, f(v, l) <n.l> / integral (GGX, height-correlated Smith, F =
// 1), in fp64.
//
// The match is measured in spherical harmonics (band-limited L2): a radially symmetric kernel about d
// projects onto Y_lm as lambda_l Y_lm(d) (Funk-Hecke), so a tap costs a Legendre series, and the error of the
// shaded result under an environment of band powers s_l is sum_l s_l sum_m (c_lm - c'_lm)^2. Each tap's
// kernel is what the chain holds: the N = V = R prefilter D(h) <n.l> at each level's roughness, blended as
// the runtime's trilinear lookup and the rough layers blend it (mip_mapping.h), for a chain of kChainLevels
// levels (256-px faces, the Frostbite mapping, with rough layers: what bakes ship).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace ibl::taps {

inline constexpr int kMaxTaps = 3;
inline constexpr int kChainLevels = 9;  // 256-px faces
inline constexpr int kMaxBand = 32;     // SH bands 0..32 in the match
inline constexpr int kGridSize = 16;    // NoV = i / 15, r = j / 15
inline constexpr double kMinNoV = 0.02; // the grid's NoV = 0 column is fitted here (V on the horizon)

struct Tap {
    double lerpFactor = 1.0; // direction normalize(lerp(N, R, t))
    double roughness = 0.0;  // the perceptual roughness the LD is read at
    double weight = 1.0;     // the taps' weights sum to 1
};

struct CellFit {
    std::array<Tap, kMaxTaps> taps{};
    int tapCount = 1;
    double residual = 0.0; // relative band-limited L2 error of the fitted sum (0 = the lobe itself)
};

// The grid cell's (NoV, r): NoV = i / (kGridSize - 1) (kMinNoV at i = 0), r = j / (kGridSize - 1).
double cellNoV(int i);
double cellRoughness(int j);

// The lobe's SH coefficients at (NoV, r) (m >= 0, cos terms only: the lobe is symmetric about the plane of
// incidence), in the frame N = +z, V in the xz plane with x > 0.
std::vector<double> lobeCoefficients(double NoV, double perceptualRoughness);

// The relative error of taps against the lobe's coefficients.
double tapsResidual(const std::vector<double>& lobe, double NoV, const Tap* taps, int tapCount);

// The best tapCount taps for one cell, Nelder-Mead from start (and from generic starts when start is empty),
// taps in increasing lerp factor.
CellFit fitCell(const std::vector<double>& lobe, double NoV, double perceptualRoughness, int tapCount,
                const CellFit* start);

// The runtime's split sum at this cell (one tap at specularDominantDirection's factor and r).
CellFit splitSumCell(double NoV, double perceptualRoughness);

// The whole table, each cell started from its fitted neighbour (rows of increasing r, NoV decreasing).
std::vector<CellFit> fitTable(int tapCount);

// kernels/specular_taps_table.h's text for a fitted table.
std::string tableHeaderText(const std::vector<CellFit>& table, int tapCount);

} // namespace ibl::taps
