// The limits that keep untrusted input (scene files written by many people, HDRIs from anywhere, run on a
// build farm) from taking unbounded memory or time. Each is defined once, here; every check says the
// allowed range in its refusal and runs before the work the limit protects
// (docs/scenes.md "Untrusted scene files").
#pragma once

#include <cstdint>

namespace ibl::limits {

// Cube faces of the source and of every product: a 4096-px RGBA32F cube is 1.6 GB with its pyramid;
// 8192 would need over 10 GB.
inline constexpr int kMaxFaceSize = 4096;

// Input images: width x height, checked from the header before a pixel is read (RGBA32F in memory:
// 4 GB at the default). The environment variable IBLBAKE_MAX_IMAGE_PIXELS sets another limit for a
// machine with more or less memory.
inline constexpr std::uint64_t kDefaultMaxImagePixels = std::uint64_t(1) << 28;
inline constexpr const char* kMaxImagePixelsVariable = "IBLBAKE_MAX_IMAGE_PIXELS";

// Image channels read at once (the span from the lowest to the highest of R, G, B); channels further
// apart (a file with render layers) are read one by one, so memory stays a few floats a pixel.
inline constexpr int kMaxChannelsRead = 4;

// Scene files and batch manifests, checked before parsing (the sample scene is under 2 KB; a manifest of
// 10,000 items under 1 MB).
inline constexpr std::uint64_t kMaxDocumentBytes = std::uint64_t(16) << 20;

// Samples per texel a user may ask for (the reference presets use 2,048 and 4,096).
inline constexpr std::uint32_t kMaxSamples = 65536;

// Scene geometry (positions, radii, half extents, fade distances) in scene units: beyond this the
// squares the runtime computes in fp32 would overflow.
inline constexpr double kMaxSceneDistance = 1e9;

// Rotations in degrees (environment, probes, box axes).
inline constexpr double kMaxRotationDegrees = 360.0;

// The sun extraction's largest bright core, steradians (--sun-max-solid-angle, environment.sunMaxSolidAngle):
// from about four texels of a 4096-px face to 0.5 sr (4% of the sphere; a softbox is 7e-3).
inline constexpr double kMinSunMaxSolidAngle = 1e-6;
inline constexpr double kMaxSunMaxSolidAngle = 0.5;

// The image pixel limit in force: IBLBAKE_MAX_IMAGE_PIXELS (a whole number from 1 to 2^40) or
// kDefaultMaxImagePixels. Throws ibl::Error naming the variable when it holds anything else.
std::uint64_t maxImagePixels();

} // namespace ibl::limits
