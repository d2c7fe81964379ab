// C++ only: OpenCL C's float8, int8 and uint8 and the built-ins the lane kernels use (lanes.h), so that the
// CPU backend compiles the same lane code the OpenCL devices run. Each type wraps a GCC/Clang vector of 8
// (vector_size(32)): the operators are the compiler's vector operations, which it emits as AVX or AVX-512
// instructions in a function built for them (the CPU backend's LD items, ld_host_items.cpp) and as pairs of
// SSE instructions otherwise. Semantics as OpenCL C 1.2 (section 6.3 and 6.12): a comparison gives -1
// (all bits) in a true lane and 0 in a false one; select(a, b, c) takes b where c is true (its lanes are
// -1 or 0 here); a scalar operand applies to every lane.
#ifndef IBL_VECTOR8_H
#define IBL_VECTOR8_H

#include <cmath>
#include <cstdint>

namespace ibl {

typedef float FloatLanes __attribute__((vector_size(32)));
typedef std::int32_t IntLanes __attribute__((vector_size(32)));
typedef std::uint32_t UintLanes __attribute__((vector_size(32)));

struct int8;
struct uint8;

struct float8 {
    FloatLanes v;
    float8() = default;
    float8(float s) : v{s, s, s, s, s, s, s, s} {}
    explicit float8(FloatLanes lanes) : v(lanes) {}
};

struct int8 {
    IntLanes v;
    int8() = default;
    int8(std::int32_t s) : v{s, s, s, s, s, s, s, s} {}
    explicit int8(IntLanes lanes) : v(lanes) {}
};

struct uint8 {
    UintLanes v;
    uint8() = default;
    uint8(std::uint32_t s) : v{s, s, s, s, s, s, s, s} {}
    explicit uint8(UintLanes lanes) : v(lanes) {}
};

// Arithmetic, lane by lane; a scalar operand converts to the vector type.
#define IBL_VECTOR8_ARITHMETIC(T, op)                                                                        \
    inline T operator op(T a, T b) {                                                                         \
        return T(a.v op b.v);                                                                                \
    }                                                                                                        \
    inline T& operator op##=(T& a, T b) {                                                                    \
        a.v = a.v op b.v;                                                                                    \
        return a;                                                                                            \
    }
IBL_VECTOR8_ARITHMETIC(float8, +)
IBL_VECTOR8_ARITHMETIC(float8, -)
IBL_VECTOR8_ARITHMETIC(float8, *)
IBL_VECTOR8_ARITHMETIC(float8, /)
IBL_VECTOR8_ARITHMETIC(int8, +)
IBL_VECTOR8_ARITHMETIC(int8, -)
IBL_VECTOR8_ARITHMETIC(int8, *)
IBL_VECTOR8_ARITHMETIC(int8, /)
IBL_VECTOR8_ARITHMETIC(int8, %)
IBL_VECTOR8_ARITHMETIC(int8, &)
IBL_VECTOR8_ARITHMETIC(int8, |)
IBL_VECTOR8_ARITHMETIC(uint8, +)
IBL_VECTOR8_ARITHMETIC(uint8, -)
IBL_VECTOR8_ARITHMETIC(uint8, *)
IBL_VECTOR8_ARITHMETIC(uint8, /)
IBL_VECTOR8_ARITHMETIC(uint8, >>)
#undef IBL_VECTOR8_ARITHMETIC

inline float8 operator-(float8 a) {
    return float8(-a.v);
}
inline int8 operator~(int8 a) {
    return int8(~a.v);
}
inline int8 operator<(int8 a, int8 b) {
    return int8(a.v < b.v);
}

// Relational built-ins (OpenCL C 6.12.6).
inline int8 isgreater(float8 a, float8 b) {
    return int8(a.v > b.v);
}
inline int8 isgreaterequal(float8 a, float8 b) {
    return int8(a.v >= b.v);
}
inline int8 isless(float8 a, float8 b) {
    return int8(a.v < b.v);
}
inline int8 islessequal(float8 a, float8 b) {
    return int8(a.v <= b.v);
}
inline bool any(int8 c) {
    for (int i = 0; i < 8; ++i)
        if (c.v[i] < 0) return true;
    return false;
}
inline float8 select(float8 a, float8 b, int8 c) {
    return float8(c.v ? b.v : a.v);
}
inline int8 select(int8 a, int8 b, int8 c) {
    return int8(c.v ? b.v : a.v);
}

// Conversions (6.2.3: float to integer rounds toward zero) and reinterpretation (6.2.4).
inline float8 convert_float8(int8 a) {
    return float8(__builtin_convertvector(a.v, FloatLanes));
}
inline float8 convert_float8(uint8 a) {
    return float8(__builtin_convertvector(a.v, FloatLanes));
}
inline int8 convert_int8(float8 a) {
    return int8(__builtin_convertvector(a.v, IntLanes));
}
inline uint8 convert_uint8(float8 a) {
    return uint8(__builtin_convertvector(a.v, UintLanes));
}
inline uint8 as_uint8(int8 a) {
    return uint8(UintLanes(a.v));
}

// Maths built-ins (6.12.2), lane by lane. fabs and copysign on the sign bit; fmax and fmin as portable.h's
// (a NaN operand loses); the rest through the scalar function in a loop the compiler turns into one vector
// instruction where there is one (sqrt, floor, ceil; built without errno: ld_host_items.cpp).
inline float8 fabs(float8 a) {
    return float8(FloatLanes(IntLanes(a.v) & 0x7FFFFFFF));
}
inline float8 copysign(float8 magnitude, float8 signSource) {
    return float8(FloatLanes((IntLanes(magnitude.v) & 0x7FFFFFFF) | (IntLanes(signSource.v) & INT32_MIN)));
}
inline float8 fmax(float8 a, float8 b) {
    return float8(((a.v > b.v) | (b.v != b.v)) ? a.v : b.v);
}
inline float8 fmin(float8 a, float8 b) {
    return float8(((a.v < b.v) | (b.v != b.v)) ? a.v : b.v);
}
inline float8 clamp(float8 x, float8 lo, float8 hi) {
    return fmin(fmax(x, lo), hi);
}
inline int8 max(int8 a, int8 b) {
    return int8(a.v > b.v ? a.v : b.v);
}
#define IBL_VECTOR8_LANEWISE(name, call)                                                                     \
    inline float8 name(float8 a) {                                                                           \
        float8 r;                                                                                            \
        for (int i = 0; i < 8; ++i)                                                                          \
            r.v[i] = call(a.v[i]);                                                                           \
        return r;                                                                                            \
    }
IBL_VECTOR8_LANEWISE(sqrt, __builtin_sqrtf)
IBL_VECTOR8_LANEWISE(floor, __builtin_floorf)
IBL_VECTOR8_LANEWISE(ceil, __builtin_ceilf)
#undef IBL_VECTOR8_LANEWISE
inline float8 atan2(float8 y, float8 x) {
    float8 r;
    for (int i = 0; i < 8; ++i)
        r.v[i] = std::atan2(y.v[i], x.v[i]);
    return r;
}

// vload8 (6.12.7): the 8 floats at p + 8 offset.
inline float8 vload8(std::uint32_t offset, const float* p) {
    float8 r;
    __builtin_memcpy(&r.v, p + 8 * offset, sizeof(r.v));
    return r;
}

// vstore8 (6.12.7): v to the 8 values at p + 8 offset.
inline void vstore8(uint8 v, std::uint32_t offset, std::uint32_t* p) {
    __builtin_memcpy(p + 8 * offset, &v.v, sizeof(v.v));
}

} // namespace ibl

#endif
