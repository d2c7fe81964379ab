// The SH window's report (iblbake/baker/sh.h shWindowText).
#include "iblbake/baker/sh.h"
#include "iblbake/core/format_text.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ibl {

std::string shWindowText(const ShWindowResult& w, int faceSize) {
    auto percent = [&](const glm::dvec3& v) { // the worst channel, relative to its mean irradiance
        double worst = std::numeric_limits<double>::infinity();
        for (int c = 0; c < 3; ++c)
            if (w.meanIrradiance[c] > 0.0) worst = std::min(worst, v[c] / w.meanIrradiance[c]);
        return std::isfinite(worst) ? 100.0 * worst : 0.0;
    };
    std::string text = formatText("sh      L2 from %d px faces; window %s", faceSize, shWindowName(w.window));
    if (w.window != ShWindow::None)
        text += formatText(" %s=%.6g", w.window == ShWindow::Sloan ? "lambda" : "w", w.parameter);
    text += formatText(" (%s), band factors %.4f %.4f\n", w.searched ? "searched" : "given", w.factors[1],
                       w.factors[2]);
    return text + formatText("        min irradiance before %.6g %.6g %.6g, after %.6g %.6g %.6g "
                             "(worst channel: %.3f%% -> %.3f%% of its mean)\n",
                             w.minBefore.x, w.minBefore.y, w.minBefore.z, w.minAfter.x, w.minAfter.y,
                             w.minAfter.z, percent(w.minBefore), percent(w.minAfter));
}

} // namespace ibl
