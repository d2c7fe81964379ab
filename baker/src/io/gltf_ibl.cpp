// glTF 2.0 output of a bake (iblbake/baker/gltf_ibl.h): EXT_lights_image_based + KHR_lights_punctual.
#include "iblbake/baker/gltf_ibl.h"
#include "iblbake/baker/rgbd.h"
#include "iblbake/core/error.h"
#include "iblbake/core/gltf_names.h"
#include "iblbake/core/numeric.h"
#include "iblbake/ktx2/atomic_file.h"
#include "iblbake/ktx2/cube_profile.h"
#include "iblbake/ktx2/output_set.h"
#include "iblbake/scene/json_vec3.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace ibl {
namespace {

namespace fs = std::filesystem;

// k_i of Y_i = k_i p_i (kernels/sh.h), in fp64.
double basisConstant(int i) {
    if (i == 0) return 0.5 / std::sqrt(kPi);
    if (i < 4) return std::sqrt(3.0 / (4.0 * kPi));
    if (i == 6) return std::sqrt(5.0 / (16.0 * kPi));
    if (i == 8) return std::sqrt(15.0 / (16.0 * kPi));
    return std::sqrt(15.0 / (4.0 * kPi));
}

// How Babylon.js reads irradianceCoefficients: SphericalHarmonics.FromArray in its basis, whose constants
// carry the Condon-Shortley sign on (1,-1), (1,1), (2,-1), (2,1), evaluated at the normal in its
// left-handed frame, where the glTF loader's root maps glTF (x, y, z) to (-x, y, z), which flips the
// terms odd in x (x, xy, xz). Written coefficient i = E_i x kBabylonSign[i] gives our E(n).
constexpr double kBabylonSign[9] = {1.0, -1.0, 1.0, 1.0, -1.0, -1.0, 1.0, 1.0, 1.0};

// Babylon.js (9.28, the extension's reference loader) uploads each specular image with its rows in the
// opposite order (the image's first row becomes the face's last, t = 1) and, in its default left-handed
// scene, shows cube direction c at glTF direction (-c.x, c.y, c.z) (same root transform; cube lookups use
// the world direction). So image f holds at column x, row r our texel of direction
// mirrorX(face f's direction at (x, N - 1 - r)): mirroring x swaps +X and -X and reverses every face's
// columns, so that is our face kMirroredFace[f] turned a half turn.
constexpr int kMirroredFace[6] = {1, 0, 2, 3, 4, 5};

ImageRGBA exportedFaceImage(const CubeMap& level, int face) {
    const ImageRGBA& source = level.faces[std::size_t(kMirroredFace[face])];
    ImageRGBA image(source.width, source.height);
    for (int r = 0; r < source.height; ++r)
        for (int x = 0; x < source.width; ++x)
            image.pixels[std::size_t(r) * std::size_t(source.width) + std::size_t(x)] =
                source.pixels[std::size_t(source.height - 1 - r) * std::size_t(source.width) +
                              std::size_t(source.width - 1 - x)];
    return image;
}

// (texel x scale)^(1 / decodeGamma) per colour channel: what an engine that raises its decoded texels to
// decodeGamma (Babylon's gammaSpace) turns back into texel x scale. Alpha is not stored (RGBD).
ImageRGBA encodedForDecodeGamma(ImageRGBA image, double scale, double decodeGamma) {
    for (glm::vec4& p : image.pixels)
        for (int c = 0; c < 3; ++c)
            p[c] = float(std::pow(std::max(double(p[c]) * scale, 0.0), 1.0 / decodeGamma));
    return image;
}

// p_i(n): 1, y, z, x, xy, yz, 3z^2 - 1, xz, x^2 - y^2.
double polynomial(int i, const glm::dvec3& n) {
    switch (i) {
    case 0:
        return 1.0;
    case 1:
        return n.y;
    case 2:
        return n.z;
    case 3:
        return n.x;
    case 4:
        return n.x * n.y;
    case 5:
        return n.y * n.z;
    case 6:
        return 3.0 * n.z * n.z - 1.0;
    case 7:
        return n.x * n.z;
    default:
        return n.x * n.x - n.y * n.y;
    }
}

void checkChain(const fs::path& path, const CubeMapChain& chain) {
    if (chain.levels.empty()) throw Error(path.string() + ": no specular levels to export");
    const int base = chain.levels.front().faceSize;
    if (base < 1 || (base & (base - 1)) != 0)
        throw Error(path.string() + ": specular face size " + std::to_string(base) +
                    " is not a power of two");
    for (std::size_t m = 0; m < chain.levels.size(); ++m)
        if (chain.levels[m].faceSize != std::max(1, base >> m))
            throw Error(path.string() + ": specular level " + std::to_string(m) + " has face size " +
                        std::to_string(chain.levels[m].faceSize) + ", expected " +
                        std::to_string(std::max(1, base >> m)));
}

nlohmann::json sunLight(const DiskLight& sun, bool inLux) {
    const double largest = std::max({sun.color.r, sun.color.g, sun.color.b});
    if (!(largest > 0.0) || !std::isfinite(sun.illuminance))
        throw Error("sun: colour or illuminance is not usable (largest channel " + std::to_string(largest) +
                    ")");
    return {{"type", "directional"},
            {"name", "sun"},
            {"color", vec3Json(sun.color / largest)},
            {"intensity", sun.illuminance * largest},
            {"extras",
             {{"iblbake.illuminanceUnits", inLux ? "lux" : "relative"},
              {"iblbake.illuminancePerpendicular", sun.illuminance},
              {"iblbake.colorLuminance1", vec3Json(sun.color)},
              {"iblbake.angularRadiusDegrees", sun.angularRadius * 180.0 / kPi}}}};
}

} // namespace

ShRgb gltfIrradianceCoefficients(const ShRgb& prescaledIrradiance) {
    ShRgb out{};
    for (int i = 0; i < 9; ++i)
        out[std::size_t(i)] = prescaledIrradiance[std::size_t(i)] * (kBabylonSign[i] / basisConstant(i));
    return out;
}

glm::dvec3 evalGltfIrradiance(const ShRgb& coefficients, const glm::dvec3& n) {
    glm::dvec3 e(0.0);
    for (int i = 0; i < 9; ++i)
        e += coefficients[std::size_t(i)] * (kBabylonSign[i] * basisConstant(i) * polynomial(i, n));
    return e;
}

double gltfIblIntensity(const GltfIblScene& scene) {
    return gltfIblIntensity(scene.specular, scene.storageScale, engineProfile(scene.profile).decodeGamma);
}

double gltfIblIntensity(const CubeMapChain& specular, double storageScale, double decodeGamma) {
    float brightest = 0.0f;
    for (const CubeMap& level : specular.levels)
        for (const ImageRGBA& face : level.faces)
            for (const glm::vec4& p : face.pixels)
                for (int c = 0; c < 3; ++c)
                    if (std::isfinite(p[c])) brightest = std::max(brightest, p[c]);
    return (brightest > 0.0f ? double(brightest) / std::pow(double(kRgbdMaxValue), decodeGamma) : 1.0) /
           storageScale;
}

std::array<double, 4> directionalLightRotation(const glm::dvec3& towardLight) {
    // The shortest-arc rotation from a to b: (a x b, 1 + a.b), normalized; a half turn about +Y when
    // b = -a (the light shining along +Z).
    const glm::dvec3 a(0.0, 0.0, -1.0), b = -glm::normalize(towardLight);
    const double w = 1.0 + glm::dot(a, b);
    if (w < 1e-12) return {0.0, 1.0, 0.0, 0.0};
    const glm::dvec3 v = glm::cross(a, b);
    const double norm = std::sqrt(glm::dot(v, v) + w * w);
    return {v.x / norm, v.y / norm, v.z / norm, w / norm};
}

void writeGltfIbl(const fs::path& path, const GltfIblScene& scene) {
    checkChain(path, scene.specular);
    const EngineProfile& profile = engineProfile(scene.profile);
    const double intensity = gltfIblIntensity(scene);
    const std::string stem = path.stem().string();

    nlohmann::json images = nlohmann::json::array();
    nlohmann::json specularImages = nlohmann::json::array();
    OutputSet outputs; // the images and the glTF that names them, all or none
    for (std::size_t m = 0; m < scene.specular.levels.size(); ++m) {
        nlohmann::json faces = nlohmann::json::array();
        for (int f = 0; f < 6; ++f) {
            const std::string name = gltfSpecularImageName(stem, int(m), f);
            outputs.writeFile(path.parent_path() / name, [&](const fs::path& temporary) {
                writeRgbdPng(temporary,
                             encodedForDecodeGamma(exportedFaceImage(scene.specular.levels[m], f),
                                                   1.0 / (intensity * scene.storageScale),
                                                   profile.decodeGamma),
                             1.0f);
            });
            faces.push_back(images.size());
            images.push_back({{"uri", name}, {"mimeType", "image/png"}});
        }
        specularImages.push_back(faces);
    }

    nlohmann::json coefficients = nlohmann::json::array();
    for (const glm::dvec3& c : gltfIrradianceCoefficients(scene.prescaledIrradiance))
        coefficients.push_back(vec3Json(c / std::pow(intensity, profile.shIntensityPower)));
    nlohmann::json extras = nlohmann::json::object();
    for (const auto& [key, value] : scene.extras)
        extras[key] = value;
    nlohmann::json ibl = {{"name", "environment"},
                          {"rotation", {0.0, 0.0, 0.0, 1.0}},
                          {"intensity", intensity},
                          {"irradianceCoefficients", coefficients},
                          {"specularImageSize", scene.specular.levels.front().faceSize},
                          {"specularImages", specularImages},
                          {"extras", extras}};

    nlohmann::json doc = {
        {"asset", {{"version", "2.0"}, {"generator", std::string("iblbake ") + IBLBAKE_VERSION}}},
        {"extensionsUsed", {"EXT_lights_image_based"}},
        {"extensions", {{"EXT_lights_image_based", {{"lights", {ibl}}}}}},
        {"images", images},
        {"scene", 0},
        {"scenes",
         {{{"name", "environment"}, {"extensions", {{"EXT_lights_image_based", {{"light", 0}}}}}}}}};
    if (scene.sun) {
        doc["extensionsUsed"].push_back("KHR_lights_punctual");
        doc["extensions"]["KHR_lights_punctual"] = {{"lights", {sunLight(*scene.sun, scene.sunInLux)}}};
        const std::array<double, 4> q = directionalLightRotation(scene.sun->direction);
        doc["nodes"] = {{{"name", "sun"},
                         {"rotation", {q[0], q[1], q[2], q[3]}},
                         {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}}};
        doc["scenes"][0]["nodes"] = {0};
    }

    outputs.writeFile(path,
                      [&](const fs::path& temporary) { writeFileBytes(temporary, doc.dump(2) + '\n'); });
    outputs.commit();
}

} // namespace ibl
