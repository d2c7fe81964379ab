// Analytic rooms of the local-probe tests: distinct wall colours, the wall a proxy-local point lies on and
// the far hit of a ray with a proxy, computed independently of kernels/parallax.h.
#pragma once

#include <iblbake/runtime/runtime.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <vector>

#include <cube.h>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

namespace rt_test {

using namespace ibl;

// Six distinct colours, one per wall (+X, -X, +Y, -Y, +Z, -Z of the proxy's frame).
inline const glm::vec3 kWallColors[6] = {{0.9f, 0.1f, 0.1f},  {0.1f, 0.8f, 0.2f}, {0.2f, 0.3f, 0.95f},
                                         {0.85f, 0.8f, 0.1f}, {0.7f, 0.1f, 0.8f}, {0.1f, 0.75f, 0.8f}};

// Wall index of a point on (or near) the proxy's surface, from its proxy-local coordinates.
inline int wallOf(const ProbeVolume& proxy, glm::vec3 local) {
    glm::vec3 q = proxy.shape == IBL_VOLUME_BOX ? local / glm::vec3(proxy.extent) : local;
    glm::vec3 a = glm::abs(q);
    if (a.x >= a.y && a.x >= a.z) return q.x >= 0 ? 0 : 1;
    if (a.y >= a.z) return q.y >= 0 ? 2 : 3;
    return q.z >= 0 ? 4 : 5;
}

// Analytic far hit of the ray (p, d) with the proxy, in proxy-local coordinates (independent of parallax.h).
inline glm::vec3 analyticHitLocal(const ProbeVolume& proxy, glm::vec3 p, glm::vec3 d) {
    glm::mat3 toLocal =
        glm::transpose(glm::mat3(glm::vec3(proxy.axisX), glm::vec3(proxy.axisY), glm::vec3(proxy.axisZ)));
    glm::dvec3 lp = glm::dvec3(toLocal * (p - glm::vec3(proxy.center)));
    glm::dvec3 ld = glm::normalize(glm::dvec3(toLocal * d));
    double t;
    if (proxy.shape == IBL_VOLUME_BOX) {
        t = 1e30;
        for (int i = 0; i < 3; ++i)
            if (ld[i] != 0.0)
                t = std::min(t, ((ld[i] > 0 ? proxy.extent[i] : -proxy.extent[i]) - lp[i]) / ld[i]);
    } else {
        double b = glm::dot(lp, ld), c = glm::dot(lp, lp) - double(proxy.extent.x) * proxy.extent.x;
        t = -b + std::sqrt(b * b - c);
    }
    return glm::vec3(lp + t * ld);
}

// The room with a window of the visibility tests: a 6 x 3 x 6 m box proxy whose capture point is 0.2 m above
// its centre, the window part of its +X wall (proxy-local coordinates).
inline const ProbeVolume kWindowRoom = boxVolume(glm::vec3(0, 1.5f, 0), glm::vec3(3, 1.5f, 3));
inline const glm::vec3 kWindowRoomCapturePoint(0.0f, 1.7f, 0.0f);
inline bool inWindow(glm::vec3 local) {
    return local.x > 2.999f && std::abs(local.y) < 0.8f && std::abs(local.z) < 1.2f;
}

// Whether every bilinear tap of direction d in an n-texel capture, and the taps' neighbours (the capture
// averages 2 x 2 sub-texels), sees the window (window) or the one wall `wall`.
inline bool tapsAgree(int n, glm::vec3 d, bool window, int wall) {
    CubeCoord c = cubeCoordFromDirection(d);
    float x = c.s * n - 0.5f, y = c.t * n - 0.5f;
    int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    for (int j = -1; j < 3; ++j)
        for (int i = -1; i < 3; ++i) {
            glm::vec3 tap = glm::normalize(
                glm::vec3(cubeFaceDirection(c.face, (x0 + i + 0.5f) / n, (y0 + j + 0.5f) / n)));
            glm::vec3 hit = analyticHitLocal(kWindowRoom, kWindowRoomCapturePoint, tap);
            if (inWindow(hit) != window || (!window && wallOf(kWindowRoom, hit) != wall)) return false;
        }
    return true;
}

// `count` mirror points in the window room (seeded), half of them looking at the window's side, and the kind
// of each for checkRoomMirrors with an n-texel capture.
struct RoomMirrorPoints {
    std::vector<ShadingPoint> points;
    std::vector<int> kind; // -1 not checked, 0..5 wall, 6 window
};
inline RoomMirrorPoints windowRoomMirrorPoints(std::size_t count, unsigned seed, int n) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    const ProbeVolume& room = kWindowRoom;
    RoomMirrorPoints out;
    while (out.points.size() < count) {
        glm::vec3 p =
            glm::vec3(room.center) + glm::vec3(u(rng), u(rng), u(rng)) * (glm::vec3(room.extent) - 0.3f);
        glm::vec3 target = out.points.size() % 2 ? glm::vec3(3.0f, 1.5f + u(rng), 1.2f * u(rng))
                                                 : p + glm::vec3(u(rng), u(rng), u(rng));
        glm::vec3 R = glm::normalize(target - p);
        glm::vec3 nrm = glm::normalize(R + glm::normalize(glm::vec3(u(rng), u(rng), u(rng))));
        glm::vec3 view = glm::reflect(-R, nrm);
        if (glm::dot(nrm, view) < 0.05f) continue;
        glm::vec3 hit = analyticHitLocal(room, p, R);
        glm::vec3 lookup = glm::normalize(glm::vec3(room.center) + hit - kWindowRoomCapturePoint);
        bool window = inWindow(hit);
        int wall = wallOf(room, hit);
        out.points.push_back(makeShadingPoint(p, nrm, view, glm::vec3(1.0f), 1.0f, 0.0f));
        out.kind.push_back(tapsAgree(n, lookup, window, wall) ? (window ? 6 : wall) : -1);
    }
    return out;
}

// The mirror points of a room with a window, shaded by `set` (specular only) on the CPU: a wall's mirror
// shows its colour, the window's `throughWindow(point, R)` with visibility 0, each within 1%. Prints the
// counts and worst errors under `label`.
struct RoomMirrors {
    int throughWindow = 0, onWall = 0;
    double worstWindow = 0.0, worstWall = 0.0; // largest relative error of a channel
};
inline RoomMirrors
checkRoomMirrors(const ProbeSet& set, RuntimeOptions options, const RoomMirrorPoints& mirrors,
                 const std::function<glm::vec3(const ShadingPoint&, glm::vec3)>& throughWindow,
                 const char* label) {
    options.diffuse = false;
    const std::vector<ShadingPoint>& points = mirrors.points;
    const std::vector<glm::vec4> out = evaluateCpu(set, points, options);
    RoomMirrors m;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const int kind = mirrors.kind[i];
        if (kind < 0) continue;
        const glm::vec3 R = glm::normalize(glm::reflect(-points[i].view, points[i].normal));
        const glm::vec3 expected = kind == 6 ? throughWindow(points[i], R) : kWallColors[kind];
        double e = 0.0;
        for (int c = 0; c < 3; ++c)
            e = std::max(e, double(std::abs(out[i][c] - expected[c]) / expected[c]));
        if (kind == 6) {
            ++m.throughWindow;
            m.worstWindow = std::max(m.worstWindow, e);
            EXPECT_EQ(out[i].w, 0.0f) << "point " << i << ": the window is transparent";
        } else {
            ++m.onWall;
            m.worstWall = std::max(m.worstWall, e);
        }
        EXPECT_LT(e, 0.01) << "point " << i << (kind == 6 ? " through the window" : " on a wall");
    }
    std::printf(
        "%s, mirrors: %d through the window (max relative error to the distant map %.2g), %d on walls "
        "(to the wall %.2g)\n",
        label, m.throughWindow, m.worstWindow, m.onWall, m.worstWall);
    return m;
}

} // namespace rt_test
