// The common subset of OpenCL C 1.2 and C++20 that every shared header is written in.
// In OpenCL C the builtin vector types and functions are used as they are; in C++ the same
// names are provided on top of GLM inside namespace ibl, so one source serves the kernels,
// the CPU backend, the reference integrators and the runtime module (pbrt-v4 style).
// The runtime's headers (probe.h and what it includes) also compile as GLSL ES 3.00 / GLSL 4.50 with
// IBL_GLSL defined (baker/runtime/glsl: probe.glsl). For that the shared code keeps to what GLSL has too:
// structs declared with IBL_STRUCT, casts through IBL_FLOAT/IBL_UINT/IBL_INT, buffers as IBL_FLOAT_BUFFER
// read with IBL_READ, conditions that are bool (flag tests written `(flags & F) != 0u`), unsigned literals
// where the other operand is unsigned (GLSL ES converts nothing implicitly), no pointers, no `static`.
#ifndef IBL_PORTABLE_H
#define IBL_PORTABLE_H

#if defined(__OPENCL_VERSION__)

#define IBL_FN static inline
// A function PoCL's inliner would leave as a call inside a hot loop: every vector register is the caller's
// to save around a call (x86-64 System V), so the loop's state went to the stack and back per call
// (brightTexelWeight in the bright pass: 10-15% of its time). The CPU backend's items are flattened anyway.
#define IBL_FN_INLINED static inline __attribute__((always_inline))
#define IBL_CONSTANT __constant
#define IBL_GLOBAL __global
#define IBL_BEGIN_NAMESPACE
#define IBL_END_NAMESPACE
#define make_float2(x, y) ((float2)((x), (y)))
#define make_float3(x, y, z) ((float3)((x), (y), (z)))
#define make_float4(x, y, z, w) ((float4)((x), (y), (z), (w)))
typedef uint uint32_t;
typedef int int32_t;
// Hot loops use this 3-float struct instead of float3: LLVM (and so PoCL) cannot vectorize a
// work-item loop that contains <3 x float> instructions, while a struct is split into scalars.
typedef struct {
    float x, y, z;
} vec3;
// On CPU devices the host defines IBL_UNIFORM_LOOP_BARRIER: a barrier at the top of a loop whose trip
// count is the same for every work-item makes PoCL emit the work-item loop innermost, inside the
// sample loop, where LLVM vectorizes it across work-items (measured 5x on the DFG kernel).
#ifdef IBL_UNIFORM_LOOP_BARRIER
#define IBL_UNIFORM_LOOP_HEAD() barrier(CLK_LOCAL_MEM_FENCE)
#else
#define IBL_UNIFORM_LOOP_HEAD()
#endif
#define IBL_SIMD_SUM(...)

#elif defined(IBL_GLSL)

// GLSL ES 3.00 / 4.50: the builtins are GLSL's; a float buffer is an offset into one data texture
// (iblData below) or whatever the integrator's iblRead reads (define IBL_GLSL_CUSTOM_READ and provide
// `float iblRead(uint index)`, e.g. over a GLSL 4.50 storage buffer).
#ifdef GL_ES
precision highp float;
precision highp int;
precision highp sampler2D;
#endif
#define IBL_FN
#define IBL_CONSTANT const
#define IBL_GLOBAL
#define IBL_BEGIN_NAMESPACE
#define IBL_END_NAMESPACE
#define IBL_UNIFORM_LOOP_HEAD()
#define IBL_STRUCT(name) struct name
#define IBL_FLOAT(x) float(x)
#define IBL_UINT(x) uint(x)
#define IBL_INT(x) int(x)
#define IBL_FLOAT_BUFFER uint
#define IBL_READ(buffer, index) iblRead((buffer) + (index))
#ifndef IBL_MAX_LOCAL_PROBES
#define IBL_MAX_LOCAL_PROBES 4
#endif
#define IBL_ARRAY_PARAM(type, name, glslSize) type name[glslSize]
#define uint32_t uint
#define int32_t int
#define float2 vec2
#define float3 vec3
#define float4 vec4
#define make_float2(x, y) vec2(x, y)
#define make_float3(x, y, z) vec3(x, y, z)
#define make_float4(x, y, z, w) vec4(x, y, z, w)
#define fabs abs
#define fmin min
#define fmax max
#define atan2 atan
// C's copysign, -0.0 included (a compare with 0 would give +1 for -0.0).
float copysign(float magnitude, float signSource) {
    return uintBitsToFloat((floatBitsToUint(magnitude) & 0x7FFFFFFFu) |
                           (floatBitsToUint(signSource) & 0x80000000u));
}
#ifndef IBL_GLSL_CUSTOM_READ
// The floats of every buffer, row-major in an R32F texture of any width (texel i at (i % width, i / width)).
uniform highp sampler2D iblData;
float iblRead(uint index) {
    uint width = uint(textureSize(iblData, 0).x);
    return texelFetch(iblData, ivec2(int(index % width), int(index / width)), 0).r;
}
#endif

#else // C++

#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>

#define IBL_FN inline
#define IBL_FN_INLINED inline
#define IBL_CONSTANT
#define IBL_GLOBAL
#define IBL_BEGIN_NAMESPACE namespace ibl {
#define IBL_END_NAMESPACE }

IBL_BEGIN_NAMESPACE
using float2 = glm::vec2;
using float3 = glm::vec3;
using float4 = glm::vec4;
using uint = std::uint32_t;
using vec3 = glm::vec3;
#define IBL_UNIFORM_LOOP_HEAD()
// Before a sample loop whose iterations are independent but for the sums named: vectorize it across
// samples (OpenMP SIMD, -fopenmp-simd on iblbake_shading, no OpenMP runtime). The lanes' partial sums
// are added at the end, so the fp32 sums differ from the scalar loop's by summation order only.
#define IBL_PRAGMA(text) _Pragma(#text)
#define IBL_SIMD_SUM(...) IBL_PRAGMA(omp simd reduction(+ : __VA_ARGS__))
using glm::clamp;
using glm::cross;
using glm::dot;
using glm::length;
using glm::mix;
using glm::normalize;
using std::acos;
using std::asin;
using std::atan;
using std::atan2;
using std::ceil;
using std::copysign;
using std::cos;
using std::fabs;
using std::floor;
using std::log2;
using std::max;
using std::min;
using std::sin;
using std::sqrt;
inline float2 make_float2(float x, float y) {
    return float2(x, y);
}
inline float3 make_float3(float x, float y, float z) {
    return float3(x, y, z);
}
inline float4 make_float4(float x, float y, float z, float w) {
    return float4(x, y, z, w);
}
// fmax/fmin as C and OpenCL define them (a NaN operand loses; of equal operands, such as -0 and +0, the
// second is returned, as glibc's do), written as selects: GCC calls glibc's fmaxf, which keeps a loop
// from vectorizing, where these become vector compares and blends.
inline float fmax(float a, float b) {
    return (a > b || b != b) ? a : b;
}
inline float fmin(float a, float b) {
    return (a < b || b != b) ? a : b;
}
// OpenCL's select(a, b, c) returns b where c is true, a otherwise.
inline float select(float a, float b, bool c) {
    return c ? b : a;
}
IBL_END_NAMESPACE

#endif

#ifndef IBL_GLSL
// The GLSL-compatible spellings (see the top) in C and C++: a struct named by a typedef (GLSL has no
// typedef), C casts, a buffer as a pointer read by indexing, an array parameter as a pointer.
#define IBL_STRUCT(name)                                                                                     \
    typedef struct name name;                                                                                \
    struct name
#define IBL_FLOAT(x) ((float)(x))
#define IBL_UINT(x) ((uint)(x))
#define IBL_INT(x) ((int)(x))
#define IBL_FLOAT_BUFFER IBL_GLOBAL const float*
#define IBL_READ(buffer, index) ((buffer)[index])
#define IBL_ARRAY_PARAM(type, name, glslSize) IBL_GLOBAL const type* name
#endif

IBL_BEGIN_NAMESPACE

#define IBL_PI 3.14159265358979323846f
#define IBL_INV_PI 0.31830988618379067154f

IBL_FN float saturate(float x) {
    return clamp(x, 0.0f, 1.0f);
}
IBL_FN float pow5(float x) {
    float x2 = x * x;
    return x2 * x2 * x;
}
IBL_FN float sq(float x) {
    return x * x;
}

// vec3 helpers: written out per component so that they scalarize in OpenCL C.
IBL_FN vec3 v3(float x, float y, float z) {
    vec3 r;
    r.x = x;
    r.y = y;
    r.z = z;
    return r;
}
IBL_FN vec3 v3add(vec3 a, vec3 b) {
    return v3(a.x + b.x, a.y + b.y, a.z + b.z);
}
IBL_FN vec3 v3sub(vec3 a, vec3 b) {
    return v3(a.x - b.x, a.y - b.y, a.z - b.z);
}
IBL_FN vec3 v3scale(vec3 a, float s) {
    return v3(a.x * s, a.y * s, a.z * s);
}
IBL_FN vec3 v3madd(vec3 a, float s, vec3 b) {
    return v3(a.x * s + b.x, a.y * s + b.y, a.z * s + b.z);
} // a*s + b
IBL_FN float v3dot(vec3 a, vec3 b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
IBL_FN vec3 v3cross(vec3 a, vec3 b) {
    return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
IBL_FN vec3 v3normalize(vec3 a) {
    return v3scale(a, 1.0f / sqrt(v3dot(a, a)));
}

// Four RGB texels of a float buffer (each at the index of its red value) weighted and summed: a bilinear
// read's taps (cube_sample.h cubeSampleLevel, textured_light.h lightCardLevel, probe.h's LUT read), in one
// order everywhere.
IBL_FN vec3 weightedRgb4(IBL_FLOAT_BUFFER data, uint i00, uint i10, uint i01, uint i11, float w00, float w10,
                         float w01, float w11) {
    return v3(w00 * IBL_READ(data, i00) + w10 * IBL_READ(data, i10) + w01 * IBL_READ(data, i01) +
                  w11 * IBL_READ(data, i11),
              w00 * IBL_READ(data, i00 + 1u) + w10 * IBL_READ(data, i10 + 1u) +
                  w01 * IBL_READ(data, i01 + 1u) + w11 * IBL_READ(data, i11 + 1u),
              w00 * IBL_READ(data, i00 + 2u) + w10 * IBL_READ(data, i10 + 2u) +
                  w01 * IBL_READ(data, i01 + 2u) + w11 * IBL_READ(data, i11 + 2u));
}

IBL_END_NAMESPACE

#endif
