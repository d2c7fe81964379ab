// shade_manifest MANIFEST: loads a scene bake through its manifest.json with the runtime module and prints
// the RGB radiance and local-probe alpha of fixed shading points, on the CPU and (when a device is found)
// through OpenCL, one point per line (%.9g). Built twice from this file: in-tree against iblbake_runtime and
// by an external project against the installed package (check_consumer.cmake compares the two outputs). Exits
// 1, naming the point, when a value is not finite or out of range, or when no point sees the local probe.
#include <iblbake/core/error.h>
#include <iblbake/opencl/executor.h>
#include <iblbake/runtime/runtime.h>
#include <iblbake/runtime/runtime_manifest.h>

#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

namespace {

// Points around the park scene's pavilion probe (data/scenes/park.json: box proxy at (20, 2, 0)) and away
// from it, dielectric and metal, from glossy to rough.
std::vector<ibl::ShadingPoint> shadingPoints() {
    std::vector<ibl::ShadingPoint> points;
    const glm::vec3 positions[] = {{20.0f, 1.0f, 0.0f}, {21.5f, 2.5f, 1.0f}, {0.0f, 0.0f, 0.0f}};
    const glm::vec3 normals[] = {{0.0f, 1.0f, 0.0f}, glm::normalize(glm::vec3(1.0f, 0.3f, -0.5f))};
    for (const glm::vec3& position : positions)
        for (const glm::vec3& normal : normals)
            for (float metallic : {0.0f, 1.0f})
                for (float perceptualRoughness : {0.1f, 0.6f})
                    points.push_back(ibl::makeShadingPoint(
                        position, normal, glm::normalize(normal + glm::vec3(0.2f, 0.4f, 0.3f)),
                        glm::vec3(0.8f, 0.6f, 0.4f), metallic, perceptualRoughness));
    return points;
}

// Prints the results; false (after saying which) when one is not finite or out of range.
bool print(const char* backend, const std::vector<glm::vec4>& results) {
    bool ok = true;
    for (std::size_t i = 0; i < results.size(); ++i) {
        const glm::vec4& r = results[i];
        std::printf("%s %zu %.9g %.9g %.9g %.9g\n", backend, i, r.r, r.g, r.b, r.a);
        const bool finite =
            std::isfinite(r.r) && std::isfinite(r.g) && std::isfinite(r.b) && std::isfinite(r.a);
        if (!finite || r.r <= 0.0f || r.g <= 0.0f || r.b <= 0.0f || r.a < 0.0f || r.a > 1.0f) {
            std::fprintf(stderr, "shade_manifest: %s point %zu out of range\n", backend, i);
            ok = false;
        }
    }
    return ok;
}

bool seesLocalProbe(const std::vector<glm::vec4>& results) {
    for (const glm::vec4& r : results)
        if (r.a > 0.0f) return true;
    return false;
}

} // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: shade_manifest MANIFEST\n");
        return 2;
    }
    try {
        const ibl::ManifestProbeSet bake = ibl::loadProbeSetFromManifest(argv[1]);
        const std::vector<ibl::ShadingPoint> points = shadingPoints();
        const std::vector<glm::vec4> cpu = ibl::evaluateCpu(bake.set, points, bake.options);
        bool ok = print("cpu", cpu);
        if (!seesLocalProbe(cpu)) {
            std::fprintf(stderr, "shade_manifest: no point sees the local probe\n");
            ok = false;
        }
        std::ostringstream warnings;
        const ibl::Executor executor = ibl::Executor::create(ibl::Backend::Auto, "", warnings);
        if (executor.usesOpenCL()) {
            ibl::OpenCLProbeEvaluator evaluator(executor.cl(), bake.set);
            ok = print("opencl", evaluator.evaluate(points, bake.options)) && ok;
        } else {
            std::printf("opencl unavailable\n");
        }
        return ok ? 0 : 1;
    } catch (const ibl::Error& e) {
        std::fprintf(stderr, "shade_manifest: error: %s\n", e.what());
        return 1;
    }
}
