#include "iblbake/baker/error_metrics.h"

#include "iblbake/baker/sh.h" // texelSolidAngle
#include "iblbake/core/error.h"

#include <algorithm>
#include <cmath>

namespace ibl {

double relativeMeanAbsError(const CubeMap& a, const CubeMap& ref) {
    return compareCubes(a, ref).relativeMeanAbs;
}

CubeErrors compareCubes(const CubeMap& a, const CubeMap& ref) {
    if (a.faceSize != ref.faceSize)
        throw Error("compareCubes: face sizes " + std::to_string(a.faceSize) + " and " +
                    std::to_string(ref.faceSize) + " differ");
    const int n = ref.faceSize;
    double absError = 0.0, absRef = 0.0, signedEnergy = 0.0, refEnergy = 0.0;
    double channelRef[3] = {0.0, 0.0, 0.0}, channelMax[3] = {0.0, 0.0, 0.0};
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const double omega = texelSolidAngle(x, y, n);
                for (int c = 0; c < 3; ++c) {
                    const double got = a.faces[f].at(x, y)[c], want = ref.faces[f].at(x, y)[c];
                    absError += std::abs(got - want);
                    absRef += std::abs(want);
                    channelRef[c] += std::abs(want);
                    channelMax[c] = std::max(channelMax[c], std::abs(got - want));
                    signedEnergy += (got - want) * omega;
                    refEnergy += want * omega;
                }
            }
    CubeErrors e;
    e.relativeMeanAbs = absRef > 0.0 ? absError / absRef : absError;
    const double texels = 6.0 * n * n;
    for (int c = 0; c < 3; ++c)
        if (channelRef[c] > 0.0)
            e.maxRelativeToMean = std::max(e.maxRelativeToMean, channelMax[c] / (channelRef[c] / texels));
    e.energy = refEnergy > 0.0 ? std::abs(signedEnergy) / refEnergy : std::abs(signedEnergy);
    return e;
}

} // namespace ibl
