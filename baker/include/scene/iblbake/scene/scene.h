// A scene file (docs/scenes.md "Scenes"): the distant environment, the local probes with their proxies, what
// the materials need and where the products go. Parsing is pure (no file system access) so that a fuzzer can
// call parseScene on arbitrary bytes; every problem is an ibl::Error "<name>: <key path>: <problem>".
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

namespace ibl {

// The CLI's calibration sources (calibration_options.h), by the same names.
enum class SceneCalibration { None, Scale, Ev100, Illuminance, SunIlluminance, SkyLuminance, Radiometric };

struct SceneCalibrationChoice {
    SceneCalibration source = SceneCalibration::None;
    double value = 0.0; // K, EV100, lux, lux, cd/m2; unused for None and Radiometric
};

struct SceneEnvironment {
    std::vector<std::filesystem::path> files; // one file, or six for layout six-files
    std::string layout = "auto";              // ingest.h parseLayout spellings
    std::string colorSpace;                   // input colour space; "" = from the file
    std::string workingColorSpace = "lin_rec709";
    double rotationDegrees = 0.0; // about +Y
    std::string latLongPixels =
        "auto"; // latlong_pixels.h parseLatLongPixels spellings: auto, centre, openexr
    SceneCalibrationChoice calibration;
    bool extractSun = false;
    // The largest bright core the extraction takes as the disk (sr; SunDetectSettings::maxSolidAngle);
    // unset: the detector's default. Only with extractSun.
    std::optional<double> sunMaxSolidAngle;
};

struct SceneVolume {
    enum class Shape { Sphere, Box } shape = Shape::Sphere;
    glm::dvec3 center{0.0};
    double radius = 0.0;             // sphere
    glm::dvec3 halfExtents{0.0};     // box
    glm::dvec3 rotationDegrees{0.0}; // box axes: R = Rz(z) Ry(y) Rx(x), x applied first
};

struct SceneProbe {
    std::string name; // [A-Za-z0-9_-], unique; names the product probe_<name>.ktx2
    std::vector<std::filesystem::path> capture;
    // The visibility as a separate image (one per capture file, the same size), replacing the capture's
    // alpha; empty: the capture's own alpha, if any (docs/scenes.md "Schema").
    std::vector<std::filesystem::path> visibilityMask;
    std::string layout = "auto";
    std::string colorSpace;
    double rotationDegrees = 0.0;
    std::string latLongPixels = "auto";
    glm::dvec3 position{0.0};             // the capture point in world space
    SceneVolume proxy;                    // its center defaults to the capture point
    std::optional<SceneVolume> influence; // default: the proxy
    double fadeDistance = 0.0;
    // Absent: the capture is scaled by the environment's calibration factor (same camera, same units).
    std::optional<SceneCalibrationChoice> calibration;
};

// lights[]: the scene's area lights. The runtime evaluates them (kernels/area_lights.h); a textured one
// (a rectangle with a texture) needs its light card baked (kernels/light_card.h), one card stage each.
// Geometry in the scene's units (metres); power as Frostbite 4.7.1: exactly one of `lumens` (luminous
// power) and `luminance` (cd/m2 of the emitting surface), the other following from Table 12.
struct SceneLight {
    std::string name;                // [A-Za-z0-9_-], unique; names the card lightcard_<name>.ktx2
    std::string shape = "rectangle"; // sphere, disk, rectangle
    std::optional<std::filesystem::path> texture; // rectangles only: the emission image
    int cardSize = 256;                           // the card's level 0, a power of two (LightCardSettings)
    int cardLayers = 8;                           // its diffuse layers
    glm::dvec3 position{0.0};                     // the centre
    glm::dvec3 normal{0.0, -1.0, 0.0};            // disk, rectangle: the emitting side (normalized)
    glm::dvec3 tangent{1.0, 0.0, 0.0};            // rectangle: the width's axis (made perpendicular)
    double width = 1.0, height = 1.0;             // rectangle
    double radius = 0.5;                          // sphere, disk
    glm::dvec3 color{1.0};                        // linear RGB in the working space, scales the emission
    std::optional<double> lumens, luminance;      // exactly one is given
};

enum class SceneDiffuseModel { Lambert, Disney };

struct SceneMaterials {
    double roughnessMin = 0.0, roughnessMax = 1.0; // perceptual roughness of the scene's materials
    SceneDiffuseModel diffuseModel = SceneDiffuseModel::Lambert;
    bool specular = true;
    bool energyCompensation = true;
    bool specularTaps = false; // materials.specularLookup "taps" (else "single": the split sum's one read)
    bool clearCoat = false;
};

// outputs.gltf: the bake as glTF 2.0, as `iblbake gltf` exports it (EXT_lights_image_based with RGBD PNG
// faces beside the .gltf, the sun as KHR_lights_punctual).
struct SceneGltfOutput {
    std::string file = "scene.gltf"; // a file name in outputs.directory, ending in .gltf
    int minFaceSize = 16;            // the roughness-1 level's face size when re-filtered (power of two)
};

// outputs.preview: the labelled material-ball grid of `iblbake preview --reference` against the full
// calibrated environment, and its linear panels beside it (<stem>.exr); the per-column error goes into the
// manifest and the bake's report.
struct ScenePreviewOutput {
    std::string file = "preview.png"; // a file name in outputs.directory, ending in .png
    int sphereSize = 64;              // pixels per ball (the reference render's cost grows with its square)
    double exposure = 0.0;            // stops
};

// What the preview's converged reference takes each roughness column to: its own estimated error, relative
// (luminance), at most this (issue 46). Not a scene key: the plan's preview-reference stage and `iblbake
// preview --reference` (material_preview.h MaterialPreviewSettings) both take it from here.
inline constexpr double kPreviewReferenceTargetError = 0.005;

struct SceneOutputs {
    std::filesystem::path directory;
    bool directoryAbsolute = false;       // written as an absolute path (refused below an output root)
    std::string ktx2Format = "rgba16f";   // rgba16f, rgba32f, b10g11r11, e5b9g9r9
    std::string profile = "standard";     // cube layout for the engine (iblbake/ktx2/cube_profile.h)
    std::string quality = "production";   // draft, production, reference
    int faceSize = 256;                   // distant LD level 0 and source cube (power of two)
    int probeFaceSize = 0;                // local probes' LD level 0; 0 = faceSize
    int dfgSize = 128;                    // DFG LUT texels per side
    std::string mipMapping = "frostbite"; // or linear
    std::string runtimeProfile;           // free text, kept in the manifest
    // Diffuse from a baked irradiance cube (irradiance.ktx2, E/pi) besides the SH: keeps what L2 SH cannot
    // (a compact light's irradiance, no ringing) at the cost of a cube lookup at run time.
    bool irradianceCube = false;
    int irradianceFaceSize = 32; // power of two
    // Clamp the KTX2 products to their format's range instead of storing them with a storage scale
    // (docs/conventions.md "Float storage and the storage scale"); the energy lost is reported.
    bool clampToFormat = false;
    std::optional<SceneGltfOutput> gltf;       // only when asked (true or an object)
    std::optional<ScenePreviewOutput> preview; // only when asked (true or an object)
};

struct Scene {
    std::string name; // for messages: the scene file as the user named it
    SceneEnvironment environment;
    std::vector<SceneProbe> probes;
    std::vector<SceneLight> lights;
    SceneMaterials materials;
    SceneOutputs outputs;
};

// Parses and validates a scene; relative paths resolve against baseDirectory (not touched). Throws
// ibl::Error "<name>: <key path>: <problem>" for malformed JSON, unknown keys, wrong types and bad values.
Scene parseScene(std::string_view text, const std::string& name, const std::filesystem::path& baseDirectory);

// Reads `path` and parses it with its directory as the base. Throws ibl::Error when it cannot be read.
Scene loadSceneFile(const std::filesystem::path& path);

const char* sceneCalibrationName(SceneCalibration source); // the JSON key: "ev100", "sunIlluminance", ...

} // namespace ibl
