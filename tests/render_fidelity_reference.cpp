// The brute-force reference of the render-fidelity harness (tests/js/render_fidelity.mjs): white metal
// spheres (base colour 1, metallic 1) of perceptual roughness 0, 0.2, ..., 1, each filling an N x N target
// under an orthographic projection, lit by an HDRI as a distant
// environment (no sun extraction), integrated by renderConvergedReference (runtime_reference.h: GGX,
// height-correlated Smith, Schlick with f0 = 1, no multiple-scattering compensation, no horizon occlusion).
//
// Geometry, in the glTF frame (docs/conventions.md's): the camera at (0, 0, -3) looks along +z, so a pixel of
// the target at (x, y) in [-1, 1]^2 (x to the right, y up, pixel centres (i + 0.5) / N * 2 - 1) with
// x^2 + y^2 < maskRadius^2 sees the point p = normal = (x, y, -sqrt(1 - x^2 - y^2)). The view is toward the
// camera's position, normalize((0, 0, -3) - p), not the projection's direction: Babylon's PBR shader takes
// V from the eye position under an orthographic projection too. Babylon's default left-handed scene shows
// glTF (x, y, z) at its (-x, y, z): the harness reads its columns mirrored. With --projection-view the view
// is the projection's direction, (0, 0, -1) at every pixel: Filament's shaders take V so under an
// orthographic projection (shading_view = the camera's backward axis; tests/js/filament_fidelity.mjs); each
// metal sphere then also carries compensatedLuminance, the same integral for Filament's material as it
// shades it: its multiple-scattering compensation 1 + f0 (1 / E - 1) (RuntimeOptions::energyCompensation, E
// the exact directional albedo) and its roughness floor (kFilamentMinPerceptualRoughness); there are no
// dielectric spheres.
//
// The split-sum floor: what a pre-filtered cube read in the mirror direction R (as Babylon reads it) shows
// at best, the same integral for the normal and view R (the lobe such a cube can hold at R) times
// E(n.v, alpha) / E(1, alpha) (the directional albedo, the part a DFG term restores). Its error against the
// reference is the split sum's own, which no cube can remove.
//
// With the optional last argument `three` (tests/js/three_fidelity.mjs), the pixels are three.js r187's: its
// shader takes V = the projection's direction under an orthographic camera (lights_fragment_begin:
// geometryViewDir = (0, 0, 1) in view space, here (0, 0, -1)), and it reads its cube not at R but at
// D = normalize(mix(R, N, r^4)) (envmap_physical_pars_fragment getIBLRadiance), so the floor is the same
// integral for the normal and view D times E(n.v) / E(1). three's camera at (0, 0, -3) looking along +z shows
// world +x on the left, as the harness's mirrored columns expect.
//
// Usage: render_fidelity_reference HDRI FACE_SIZE PIXELS MASK_RADIUS OUT.json [three | --projection-view]
// Writes { pixels, maskRadius, faceSize, roughness: [...], spheres: [{ roughness, luminance: [per masked
// pixel, rows bottom to top], splitSumLuminance [the same pixels], directionalAlbedo [E(n.v, alpha) of the
// same pixels, the floor's factor over E(1, alpha)], meanLuminance, errorEstimate (relative, of the mean) }],
// dielectricSpheres: [the same without splitSumLuminance] }. The dielectric spheres: base colour 1, metallic
// 0, f0 0.04, Lambert diffuse (base colour / pi, no (1 - F) weight), the same pixels.
#include <iblbake/baker/ingest.h>
#include <iblbake/core/error.h>
#include <iblbake/runtime/runtime_reference.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>

#include <glm/geometric.hpp>
#include <string>

namespace {

constexpr double kEyeDistance = 3.0; // render_fidelity_page.js's camera
constexpr std::uint32_t kAlbedoSamples = 1024;

double luminance(const glm::dvec3& c) {
    return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

// Filament's shaders for TARGET_MOBILE, which its WebGL build runs, clamp the perceptual roughness to 0.089
// (common_material.fs MIN_PERCEPTUAL_ROUGHNESS: the smallest r with r^4 > 0 in fp16): its r = 0 sphere is an
// r = 0.089 one.
constexpr float kFilamentMinPerceptualRoughness = 0.089f;

} // namespace

int main(int argc, char** argv) {
    const std::string mode = argc == 7 ? argv[6] : "";
    const bool three = mode == "three", filament = mode == "--projection-view";
    const bool projectionView = three || filament;
    if (argc != 6 && !projectionView) {
        std::fprintf(stderr, "usage: render_fidelity_reference HDRI FACE_SIZE PIXELS MASK_RADIUS OUT.json "
                             "[three | --projection-view]\n");
        return 2;
    }
    try {
        const auto start = std::chrono::steady_clock::now();
        ibl::IngestSettings ingest;
        ingest.sourceFaceSize = std::stoi(argv[2]);
        const ibl::CubeMap environment = ibl::ingestEnvironment({argv[1]}, ingest).cube;
        const int pixels = std::stoi(argv[3]);
        const double maskRadius = std::stod(argv[4]);

        ibl::RuntimeOptions options;
        options.diffuse = false; // white metal: specular only
        options.energyCompensation = false;
        ibl::RuntimeOptions compensatedOptions = options;
        compensatedOptions.energyCompensation = true;
        ibl::RuntimeOptions dielectricOptions = options;
        dielectricOptions.diffuse = true;
        nlohmann::json out = {{"pixels", pixels},
                              {"maskRadius", maskRadius},
                              {"faceSize", ingest.sourceFaceSize},
                              {"engine", three      ? "three"
                                         : filament ? "filament"
                                                    : "babylon"}};
        for (int step = 0; step <= 5; ++step) {
            const float roughness = float(step) / 5.0f;
            std::vector<ibl::ShadingPoint> points;
            for (int row = 0; row < pixels; ++row)
                for (int column = 0; column < pixels; ++column) {
                    const double x = (column + 0.5) / pixels * 2.0 - 1.0,
                                 y = (row + 0.5) / pixels * 2.0 - 1.0;
                    if (x * x + y * y >= maskRadius * maskRadius) continue;
                    ibl::ShadingPoint p{};
                    p.normal = {float(x), float(y), float(-std::sqrt(1.0 - x * x - y * y))};
                    p.position = p.normal;
                    p.view = projectionView ? glm::vec3(0.0f, 0.0f, -1.0f)
                                            : glm::vec3(0.0f, 0.0f, -float(kEyeDistance)) - p.position;
                    p.baseColor = {1.0f, 1.0f, 1.0f};
                    p.metallic = 1.0f;
                    p.perceptualRoughness = roughness;
                    p.ao = 1.0f;
                    points.push_back(p);
                }
            const ibl::ConvergedReference reference =
                ibl::renderConvergedReference(environment, points, options);
            std::vector<ibl::ShadingPoint> mirrored = points;
            std::vector<double> albedoRatio, albedo;
            const double alpha = std::max(double(roughness) * roughness, 1e-4);
            const double albedoAtNormalIncidence = ibl::directionalAlbedo(1.0, alpha, kAlbedoSamples);
            for (ibl::ShadingPoint& p : mirrored) {
                const glm::dvec3 n = glm::dvec3(p.normal), v = glm::normalize(glm::dvec3(p.view));
                const glm::dvec3 mirror = 2.0 * glm::dot(n, v) * n - v;
                const double bend = three ? std::pow(double(roughness), 4.0) : 0.0;
                const glm::dvec3 r = glm::normalize(mirror + bend * (n - mirror));
                albedo.push_back(ibl::directionalAlbedo(glm::dot(n, v), alpha, kAlbedoSamples));
                albedoRatio.push_back(albedo.back() / albedoAtNormalIncidence);
                p.normal = p.view = glm::vec3(r);
            }
            const ibl::ConvergedReference splitSum =
                ibl::renderConvergedReference(environment, mirrored, options);
            nlohmann::json values = nlohmann::json::array(), floor = nlohmann::json::array();
            double sum = 0.0, error = 0.0;
            for (std::size_t k = 0; k < points.size(); ++k) {
                const double value = luminance(reference.results[k].total());
                values.push_back(value);
                floor.push_back(luminance(splitSum.results[k].total()) * albedoRatio[k]);
                sum += value;
                error += luminance(reference.errorEstimate[k]);
            }
            out["spheres"].push_back({{"roughness", roughness},
                                      {"luminance", values},
                                      {"splitSumLuminance", floor},
                                      {"directionalAlbedo", albedo},
                                      {"meanLuminance", sum / double(points.size())},
                                      {"errorEstimate", error / sum}});
            std::printf("reference r = %.1f: %zu pixels, mean luminance %.6g, estimated error %.4f%%\n",
                        roughness, points.size(), sum / double(points.size()), 100.0 * error / sum);
            if (filament) {
                std::vector<ibl::ShadingPoint> material = points;
                for (ibl::ShadingPoint& p : material)
                    p.perceptualRoughness = std::max(p.perceptualRoughness, kFilamentMinPerceptualRoughness);
                const ibl::ConvergedReference compensated =
                    ibl::renderConvergedReference(environment, material, compensatedOptions);
                nlohmann::json compensatedValues = nlohmann::json::array();
                for (const ibl::ReferenceResult& result : compensated.results)
                    compensatedValues.push_back(luminance(result.total()));
                out["spheres"].back()["compensatedLuminance"] = compensatedValues;
            }
            if (filament) continue; // the Filament harness renders metal only
            for (ibl::ShadingPoint& p : points)
                p.metallic = 0.0f;
            const ibl::ConvergedReference dielectric =
                ibl::renderConvergedReference(environment, points, dielectricOptions);
            nlohmann::json dielectricValues = nlohmann::json::array();
            double dielectricSum = 0.0, dielectricError = 0.0;
            for (std::size_t k = 0; k < points.size(); ++k) {
                dielectricValues.push_back(luminance(dielectric.results[k].total()));
                dielectricSum += dielectricValues.back().get<double>();
                dielectricError += luminance(dielectric.errorEstimate[k]);
            }
            out["dielectricSpheres"].push_back({{"roughness", roughness},
                                                {"luminance", dielectricValues},
                                                {"meanLuminance", dielectricSum / double(points.size())},
                                                {"errorEstimate", dielectricError / dielectricSum}});
            std::printf("reference dielectric r = %.1f: mean luminance %.6g, estimated error %.4f%%\n",
                        roughness, dielectricSum / double(points.size()),
                        100.0 * dielectricError / dielectricSum);
        }
        std::ofstream(argv[5]) << out.dump() << '\n';
        std::printf("reference time %.1f s\n",
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "render_fidelity_reference: %s\n", e.what());
        return 1;
    }
}
