// Analytic rooms of the local-probe tests: distinct wall colours, the wall a proxy-local point lies on and
// the far hit of a ray with a proxy, computed independently of kernels/parallax.h.
#pragma once

#include <iblbake/runtime/runtime.h>

#include <algorithm>
#include <cmath>

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

} // namespace rt_test
