// Cube-map and lat-long addressing (docs/conventions.md "Directions and cube faces", "Lat-long mapping and
// pixel placement"). Faces are in KTX2/Vulkan/OpenGL order +X, -X, +Y, -Y, +Z, -Z with the OpenGL
// orientation; within a face, s runs along a row and t down the rows (t = 0 is the first row in memory),
// texel (i, j) of an N-texel face has its centre at s = (i + 0.5) / N, t = (j + 0.5) / N.
#ifndef IBL_CUBE_H
#define IBL_CUBE_H

#include "portable.h"

IBL_BEGIN_NAMESPACE

IBL_STRUCT(CubeCoord) {
    int face; // 0..5: +X, -X, +Y, -Y, +Z, -Z
    float s;  // [0, 1] along the face's row
    float t;  // [0, 1] down the face's rows
};

// Unnormalized direction through (s, t) of a face (OpenGL table "Selection of cube map images").
IBL_FN vec3 cubeFaceDirection(int face, float s, float t) {
    float sc = 2.0f * s - 1.0f, tc = 2.0f * t - 1.0f;
    vec3 d = v3(-sc, -tc, -1.0f); // -Z
    d = face == 0 ? v3(1.0f, -tc, -sc) : d;
    d = face == 1 ? v3(-1.0f, -tc, sc) : d;
    d = face == 2 ? v3(sc, 1.0f, tc) : d;
    d = face == 3 ? v3(sc, -1.0f, -tc) : d;
    d = face == 4 ? v3(sc, -tc, 1.0f) : d;
    return d;
}

// Unit direction through the centre of texel (x, y) of an n-texel face.
IBL_FN vec3 cubeTexelDirection(int face, uint x, uint y, uint n) {
    return v3normalize(
        cubeFaceDirection(face, (IBL_FLOAT(x) + 0.5f) / IBL_FLOAT(n), (IBL_FLOAT(y) + 0.5f) / IBL_FLOAT(n)));
}

// Face and (s, t) hit by a direction (need not be normalized; must not be zero). Ties between
// axes of equal magnitude go to X, then Y, as in the OpenGL selection rule. Written with selects
// only, so that work-items taking different faces stay vectorized together.
IBL_FN CubeCoord cubeCoordFromDirection(vec3 d) {
    float ax = fabs(d.x), ay = fabs(d.y), az = fabs(d.z);
    bool xMajor = ax >= ay && ax >= az;
    bool yMajor = !xMajor && ay >= az;
    bool zMajor = !xMajor && !yMajor;
    CubeCoord c;
    c.face = xMajor ? (d.x >= 0.0f ? 0 : 1) : yMajor ? (d.y >= 0.0f ? 2 : 3) : (d.z >= 0.0f ? 4 : 5);
    float ma = xMajor ? ax : yMajor ? ay : az;
    float sc = xMajor ? (d.x >= 0.0f ? -d.z : d.z) : (zMajor && d.z < 0.0f ? -d.x : d.x);
    float tc = yMajor ? (d.y >= 0.0f ? d.z : -d.z) : -d.y;
    float inv = 0.5f / ma;
    c.s = sc * inv + 0.5f;
    c.t = tc * inv + 0.5f;
    return c;
}

// Solid angle of the face region [0, x] x [0, y] in face-plane coordinates (x, y in [-1, 1] measured
// from the face centre): atan2(x y, sqrt(x^2 + y^2 + 1)). Differences of it give a texel's exact
// solid angle (the area-element integral of the cube face).
IBL_FN float cubeAreaElement(float x, float y) {
    return atan2(x * y, sqrt(x * x + y * y + 1.0f));
}

#ifdef __cplusplus
// cubeAreaElement in fp64, for the host's exact-area tables and references: in float, the four-term
// difference that gives a sub-texel's solid angle loses most of it on large faces (eps / step^2).
inline double cubeAreaElementF64(double x, double y) {
    return std::atan2(x * y, std::sqrt(x * x + y * y + 1.0));
}

// Solid angle of the face-plane rectangle [x0, x1] x [y0, y1] in fp64 (the four-term difference of
// cubeAreaElementF64; negative when the rectangle's corners are given in reverse).
inline double cubeRectangleSolidAngleF64(double x0, double y0, double x1, double y1) {
    return cubeAreaElementF64(x0, y0) - cubeAreaElementF64(x0, y1) - cubeAreaElementF64(x1, y0) +
           cubeAreaElementF64(x1, y1);
}
#endif

// Exact solid angle of texel (i, j) of an N-texel face.
IBL_FN float cubeTexelSolidAngle(int i, int j, int n) {
    float inv = 2.0f / IBL_FLOAT(n);
    float x0 = IBL_FLOAT(i) * inv - 1.0f, x1 = x0 + inv;
    float y0 = IBL_FLOAT(j) * inv - 1.0f, y1 = y0 + inv;
    return cubeAreaElement(x0, y0) - cubeAreaElement(x0, y1) - cubeAreaElement(x1, y0) +
           cubeAreaElement(x1, y1);
}

// Solid angle of the square [u0, u0 + step] x [v0, v0 + step] of a face (face-plane coordinates), in
// float without cancellation: the four-term difference of cubeAreaElement loses about eps / step^2 of
// its value (100% for the sub-texels of a 256 px face), the midpoint rule of the area element
// (1 + u^2 + v^2)^(-3/2) du dv errs by about step^2 / 8. Below step 1/32 the midpoint rule is the more
// accurate (both ~1e-4 there).
IBL_FN float cubePatchSolidAngle(float u0, float v0, float step) {
    if (step >= 0.03125f)
        return fabs(cubeAreaElement(u0, v0) - cubeAreaElement(u0, v0 + step) -
                    cubeAreaElement(u0 + step, v0) + cubeAreaElement(u0 + step, v0 + step));
    float u = u0 + 0.5f * step, v = v0 + 0.5f * step;
    float r2 = 1.0f + u * u + v * v;
    return step * step / (r2 * sqrt(r2));
}

// Lat-long (equirect) mapping of OpenEXR's ImfEnvmap LatLongMap: longitude = atan2(x, z),
// latitude = asin(y); u = 0.5 - longitude / (2 pi), v = 0.5 - latitude / pi. The image centre looks
// toward +Z, the first scanline is +Y, +X is at u = 0.25.
IBL_FN float2 latlongFromDirection(vec3 d) {
    vec3 n = v3normalize(d);
    float longitude = atan2(n.x, n.z);
    float latitude = asin(clamp(n.y, -1.0f, 1.0f));
    return make_float2(0.5f - longitude * (0.5f * IBL_INV_PI), 0.5f - latitude * IBL_INV_PI);
}

IBL_FN vec3 directionFromLatlong(float u, float v) {
    float longitude = (0.5f - u) * 2.0f * IBL_PI;
    float latitude = (0.5f - v) * IBL_PI;
    float c = cos(latitude);
    return v3(c * sin(longitude), sin(latitude), c * cos(longitude));
}

IBL_END_NAMESPACE

#endif
