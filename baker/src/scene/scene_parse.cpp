// Scene file parsing and validation (docs/scenes.md "Schema"). Every accessor knows its key path, so each
// error names it; keys are consumed as read and whatever is left in an object is an unknown key (a typo must
// not be silently ignored).
#include "iblbake/core/numeric.h"
#include "iblbake/scene/scene.h"

#include "iblbake/core/error.h"
#include "iblbake/core/input_file.h"
#include "iblbake/core/limits.h"
#include "iblbake/core/output_path.h"
#include "iblbake/ktx2/cube_profile.h"
#include "iblbake/ktx2/ktx2.h"

#include <mip_mapping.h>
#include <nlohmann/json.hpp>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>
#include <set>

namespace ibl {

namespace {

using nlohmann::json;
namespace fs = std::filesystem;

class Fail {
  public:
    explicit Fail(std::string name) : name_(std::move(name)) {}
    [[noreturn]] void operator()(const std::string& path, const std::string& problem) const {
        throw Error(name_ + ": " + (path.empty() ? "" : path + ": ") + problem);
    }

  private:
    std::string name_;
};

// A limit or a value for a message: "1e+09", "360", "-1.5".
std::string shortNumber(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", value);
    return text;
}

constexpr double kMaxDistance = limits::kMaxSceneDistance;
constexpr double kMaxDegrees = limits::kMaxRotationDegrees;
constexpr double kMinSunMaxSolidAngle = limits::kMinSunMaxSolidAngle;
constexpr double kMaxSunMaxSolidAngle = limits::kMaxSunMaxSolidAngle;

const char* typeName(const json& v) {
    return v.is_object()    ? "an object"
           : v.is_array()   ? "an array"
           : v.is_string()  ? "a string"
           : v.is_boolean() ? "a boolean"
           : v.is_number()  ? "a number"
                            : "null";
}

// One JSON object being read: get*() take a key out; finish() rejects what is left.
class ObjectReader {
  public:
    ObjectReader(const json& value, std::string path, const Fail& fail)
        : path_(std::move(path)), fail_(fail) {
        if (!value.is_object()) fail_(path_, std::string("must be an object, not ") + typeName(value));
        for (auto it = value.begin(); it != value.end(); ++it)
            remaining_.emplace(it.key());
        value_ = &value;
    }

    std::string key(const std::string& k) const { return path_.empty() ? k : path_ + "." + k; }
    bool has(const std::string& k) const { return value_->contains(k); }

    const json* take(const std::string& k) {
        remaining_.erase(k);
        auto it = value_->find(k);
        return it == value_->end() ? nullptr : &*it;
    }
    const json& required(const std::string& k) {
        const json* v = take(k);
        if (!v) fail_(key(k), "is required");
        return *v;
    }

    double number(const std::string& k, double fallback) {
        const json* v = take(k);
        return v ? numberValue(*v, key(k)) : fallback;
    }
    double numberValue(const json& v, const std::string& path) const {
        if (!v.is_number()) fail_(path, std::string("must be a number, not ") + typeName(v));
        double d = v.get<double>();
        if (!std::isfinite(d)) fail_(path, "must be a finite number");
        return d;
    }
    // A number from lo to hi: the allowed range is in the refusal (limits.h).
    double number(const std::string& k, double fallback, double lo, double hi) {
        const json* v = take(k);
        return v ? inRange(numberValue(*v, key(k)), key(k), lo, hi) : fallback;
    }
    double inRange(double d, const std::string& path, double lo, double hi) const {
        if (!(d >= lo && d <= hi))
            fail_(path, "must be a number from " + shortNumber(lo) + " to " + shortNumber(hi) + ", not " +
                            shortNumber(d));
        return d;
    }
    int integer(const std::string& k, int fallback, int lo, int hi) {
        const json* v = take(k);
        if (!v) return fallback;
        double d = numberValue(*v, key(k));
        if (d != std::floor(d) || d < lo || d > hi)
            fail_(key(k), "must be a whole number from " + std::to_string(lo) + " to " + std::to_string(hi));
        return int(d);
    }
    bool boolean(const std::string& k, bool fallback) {
        const json* v = take(k);
        if (!v) return fallback;
        if (!v->is_boolean()) fail_(key(k), std::string("must be true or false, not ") + typeName(*v));
        return v->get<bool>();
    }
    std::string string(const std::string& k, const std::string& fallback) {
        const json* v = take(k);
        return v ? stringValue(*v, key(k)) : fallback;
    }
    std::string stringValue(const json& v, const std::string& path) const {
        if (!v.is_string()) fail_(path, std::string("must be a string, not ") + typeName(v));
        return v.get<std::string>();
    }
    std::string choice(const std::string& k, const std::string& fallback,
                       const std::vector<std::string>& allowed) {
        std::string s = string(k, fallback);
        for (const std::string& a : allowed)
            if (s == a) return s;
        std::string list;
        for (const std::string& a : allowed)
            list += (list.empty() ? "" : ", ") + a;
        fail_(key(k), valueForMessage(s) + " is not one of " + list);
    }
    glm::dvec3 vec3(const std::string& k, const glm::dvec3& fallback, double lo, double hi,
                    const char* what = "3 numbers") {
        const json* v = take(k);
        if (!v) return fallback;
        if (!v->is_array() || v->size() != 3) fail_(key(k), std::string("must be ") + what);
        glm::dvec3 out;
        for (int i = 0; i < 3; ++i) {
            if (!(*v)[std::size_t(i)].is_number()) fail_(key(k), std::string("must be ") + what);
            out[i] = inRange(numberValue((*v)[std::size_t(i)], key(k)), key(k), lo, hi);
        }
        return out;
    }

    void finish() const {
        if (remaining_.empty()) return;
        fail_(key(printableForMessage(*remaining_.begin())), "unknown key");
    }
    const Fail& fail() const { return fail_; }

  private:
    const json* value_ = nullptr;
    std::string path_;
    const Fail& fail_;
    std::set<std::string> remaining_;
};

// A preview's exposure in stops: 2^64 keeps every pixel's scale finite.
constexpr double kMaxExposureStops = 64.0;

fs::path resolve(const std::string& file, const fs::path& base) {
    fs::path p(file);
    return (p.is_absolute() ? p : base / p).lexically_normal();
}

// "file": "a.hdr" or ["+x.hdr", ..., "-z.hdr"] (six-files layout).
std::vector<fs::path> files(ObjectReader& r, const std::string& k, const fs::path& base) {
    const json& v = r.required(k);
    std::vector<fs::path> out;
    if (v.is_string()) {
        out.push_back(resolve(r.stringValue(v, r.key(k)), base));
    } else if (v.is_array() && (v.size() == 6)) {
        for (std::size_t i = 0; i < v.size(); ++i)
            out.push_back(resolve(r.stringValue(v[i], r.key(k) + "[" + std::to_string(i) + "]"), base));
    } else {
        r.fail()(r.key(k), "must be a file name or an array of six (six-files layout)");
    }
    for (const fs::path& p : out)
        if (p.empty() || !p.has_filename())
            r.fail()(r.key(k), "must name a file");
        else if (hasControlBytes(p.string())) // a NUL would cut the name short where the system reads it
            r.fail()(r.key(k), quotedForMessage(p.string()) + " holds control bytes, which no file name may");
    return out;
}

const std::vector<std::string> kLayouts = {"auto",   "latlong", "exr-cube", "hcross",
                                           "vcross", "hstrip",  "vstrip",   "six-files"};

const std::vector<std::string> kLatLongPixels = {"auto", "centre", "openexr"};

void checkLayoutFileCount(ObjectReader& r, const std::string& layoutKey, const std::string& layout,
                          std::size_t fileCount) {
    if ((layout == "six-files") != (fileCount == 6))
        r.fail()(r.key(layoutKey), layout == "six-files" ? "six-files needs an array of six files"
                                                         : "an array of six files needs layout six-files");
}

// {"ev100": 12} and the other calibration sources: exactly one key.
SceneCalibrationChoice calibration(const json& v, const std::string& path, const Fail& fail) {
    ObjectReader r(v, path, fail);
    SceneCalibrationChoice c;
    int count = 0;
    for (SceneCalibration s :
         {SceneCalibration::Scale, SceneCalibration::Ev100, SceneCalibration::Illuminance,
          SceneCalibration::SunIlluminance, SceneCalibration::SkyLuminance}) {
        const std::string k = sceneCalibrationName(s);
        if (!r.has(k)) continue;
        ++count;
        c.source = s;
        c.value = r.number(k, 0.0);
        bool positive = s != SceneCalibration::Ev100;
        if (positive && !(c.value > 0.0)) fail(r.key(k), "must be a positive number");
    }
    if (r.has("radiometric")) {
        if (r.boolean("radiometric", false)) {
            ++count;
            c.source = SceneCalibration::Radiometric;
        }
    }
    r.finish();
    if (count > 1)
        fail(path, "give one calibration source (scale, ev100, illuminance, sunIlluminance, skyLuminance, "
                   "radiometric)");
    return c;
}

SceneVolume volume(const json& v, const std::string& path, const Fail& fail,
                   const std::optional<glm::dvec3>& defaultCenter) {
    ObjectReader r(v, path, fail);
    SceneVolume out;
    r.required("shape");
    const std::string shape = r.choice("shape", "", {"sphere", "box"});
    out.shape = shape == "sphere" ? SceneVolume::Shape::Sphere : SceneVolume::Shape::Box;
    if (!defaultCenter && !r.has("center")) fail(r.key("center"), "is required");
    out.center = r.vec3("center", defaultCenter.value_or(glm::dvec3(0.0)), -kMaxDistance, kMaxDistance);
    if (out.shape == SceneVolume::Shape::Sphere) {
        if (!r.has("radius")) fail(r.key("radius"), "is required for a sphere");
        out.radius = r.number("radius", 0.0, 0.0, kMaxDistance);
        if (!(out.radius > 0.0)) fail(r.key("radius"), "must be a positive number");
    } else {
        if (!r.has("halfExtents")) fail(r.key("halfExtents"), "is required for a box");
        out.halfExtents = r.vec3("halfExtents", glm::dvec3(0.0), 0.0, kMaxDistance, "3 positive numbers");
        for (int i = 0; i < 3; ++i)
            if (!(out.halfExtents[i] > 0.0)) fail(r.key("halfExtents"), "must be 3 positive numbers");
        out.rotationDegrees = r.vec3("rotation", glm::dvec3(0.0), -kMaxDegrees, kMaxDegrees);
    }
    r.finish();
    return out;
}

SceneEnvironment environment(const json& v, const fs::path& base, const Fail& fail) {
    ObjectReader r(v, "environment", fail);
    SceneEnvironment e;
    e.files = files(r, "file", base);
    e.layout = r.choice("layout", "auto", kLayouts);
    checkLayoutFileCount(r, "layout", e.layout, e.files.size());
    e.colorSpace = r.string("colorSpace", "");
    e.workingColorSpace = r.choice("workingColorSpace", "lin_rec709", {"lin_rec709", "acescg"});
    e.rotationDegrees = r.number("rotation", 0.0, -kMaxDegrees, kMaxDegrees);
    e.latLongPixels = r.choice("latlongPixels", "auto", kLatLongPixels);
    if (const json* c = r.take("calibration")) e.calibration = calibration(*c, r.key("calibration"), fail);
    e.extractSun = r.boolean("extractSun", false);
    if (r.has("sunMaxSolidAngle")) {
        e.sunMaxSolidAngle = r.number("sunMaxSolidAngle", 0.0, kMinSunMaxSolidAngle, kMaxSunMaxSolidAngle);
        if (!e.extractSun) fail(r.key("sunMaxSolidAngle"), "needs environment.extractSun");
    }
    r.finish();
    return e;
}

bool validProbeName(const std::string& name) {
    if (name.empty() || name.size() > 64) return false;
    for (char ch : name)
        if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '_' && ch != '-') return false;
    return true;
}

SceneProbe probe(const json& v, const std::string& path, const fs::path& base, const Fail& fail) {
    ObjectReader r(v, path, fail);
    SceneProbe p;
    p.name = r.string("name", "");
    if (!validProbeName(p.name)) fail(r.key("name"), "must be 1 to 64 of A-Z a-z 0-9 _ -");
    p.capture = files(r, "capture", base);
    p.layout = r.choice("layout", "auto", kLayouts);
    checkLayoutFileCount(r, "layout", p.layout, p.capture.size());
    if (r.has("visibilityMask")) {
        p.visibilityMask = files(r, "visibilityMask", base);
        if (p.visibilityMask.size() != p.capture.size())
            fail(r.key("visibilityMask"),
                 "needs one file per capture file (" + std::to_string(p.capture.size()) + ")");
    }
    p.colorSpace = r.string("colorSpace", "");
    p.rotationDegrees = r.number("rotation", 0.0, -kMaxDegrees, kMaxDegrees);
    p.latLongPixels = r.choice("latlongPixels", "auto", kLatLongPixels);
    if (!r.has("position")) fail(r.key("position"), "is required");
    p.position = r.vec3("position", glm::dvec3(0.0), -kMaxDistance, kMaxDistance);
    p.proxy = volume(r.required("proxy"), r.key("proxy"), fail, p.position);
    if (const json* i = r.take("influence"))
        p.influence = volume(*i, r.key("influence"), fail, p.proxy.center);
    p.fadeDistance = r.number("fadeDistance", 0.0, 0.0, kMaxDistance);
    if (const json* c = r.take("calibration")) p.calibration = calibration(*c, r.key("calibration"), fail);
    r.finish();
    return p;
}

SceneMaterials materials(const json& v, const Fail& fail) {
    ObjectReader r(v, "materials", fail);
    SceneMaterials m;
    if (const json* range = r.take("roughness")) {
        ObjectReader rr(*range, r.key("roughness"), fail);
        m.roughnessMin = rr.number("min", 0.0);
        m.roughnessMax = rr.number("max", 1.0);
        rr.finish();
        if (m.roughnessMin < 0.0 || m.roughnessMin > 1.0) fail(rr.key("min"), "must be from 0 to 1");
        if (m.roughnessMax < 0.0 || m.roughnessMax > 1.0) fail(rr.key("max"), "must be from 0 to 1");
        if (m.roughnessMin > m.roughnessMax) fail(r.key("roughness"), "min must not exceed max");
    }
    m.diffuseModel = r.choice("diffuseModel", "lambert", {"lambert", "disney"}) == "disney"
                         ? SceneDiffuseModel::Disney
                         : SceneDiffuseModel::Lambert;
    m.specular = r.boolean("specular", true);
    m.energyCompensation = r.boolean("energyCompensation", true);
    m.specularTaps = r.choice("specularLookup", "single", {"single", "taps"}) == "taps";
    m.clearCoat = r.boolean("clearCoat", false);
    r.finish();
    return m;
}

// An output file's name: a plain file name in outputs.directory with the given extension.
std::string outputFileName(ObjectReader& r, const std::string& k, const std::string& fallback,
                           const std::string& extension, const Fail& fail) {
    const std::string name = r.string(k, fallback);
    const fs::path path(name);
    if (name.empty() || path.filename() != path || path.stem().empty() || path.stem() == "." ||
        path.extension() != extension)
        fail(r.key(k), valueForMessage(name) + " must be a file name ending in " + extension);
    return name;
}

// true, false, or an object of settings: the output is made only when asked.
template <class Output, class Read>
std::optional<Output> optionalOutput(ObjectReader& outputs, const std::string& k, const Fail& fail,
                                     Read read) {
    const json* v = outputs.take(k);
    if (!v || (v->is_boolean() && !v->get<bool>())) return std::nullopt;
    if (v->is_boolean()) return Output{};
    if (!v->is_object())
        fail(outputs.key(k), std::string("must be true, false or an object, not ") + typeName(*v));
    ObjectReader r(*v, outputs.key(k), fail);
    Output out = read(r);
    r.finish();
    return out;
}

SceneLight light(const json& v, const std::string& path, const fs::path& base, const Fail& fail) {
    ObjectReader r(v, path, fail);
    SceneLight l;
    l.name = r.string("name", "");
    if (!validProbeName(l.name)) fail(r.key("name"), "must be 1 to 64 of A-Z a-z 0-9 _ -");
    l.shape = r.choice("shape", "rectangle", {"sphere", "disk", "rectangle"});
    if (r.has("texture")) {
        const std::vector<fs::path> file = files(r, "texture", base);
        if (file.size() != 1) fail(r.key("texture"), "must be one file name");
        if (l.shape != "rectangle") fail(r.key("texture"), "only a rectangle light can be textured");
        l.texture = file.front();
    }
    l.cardSize = r.integer("cardSize", l.cardSize, 4, 4096);
    if (!isPowerOfTwo(l.cardSize)) fail(r.key("cardSize"), "must be a power of two");
    l.cardLayers = r.integer("cardLayers", l.cardLayers, 2, 64);
    if (!l.texture && (r.has("cardSize") || r.has("cardLayers")))
        fail(r.key(r.has("cardSize") ? "cardSize" : "cardLayers"),
             "needs a texture: only textured lights have cards");
    // Geometry: each key only where the shape has it, so that none is silently ignored.
    const bool sphere = l.shape == "sphere", rectangle = l.shape == "rectangle";
    for (const char* k : {"normal", "tangent", "width", "height", "radius"}) {
        const bool applies = std::string(k) == "radius"   ? !rectangle
                             : std::string(k) == "normal" ? !sphere
                                                          : rectangle;
        if (!applies && r.has(k)) fail(r.key(k), "a " + l.shape + " light has none");
    }
    l.position = r.vec3("position", l.position, -kMaxDistance, kMaxDistance);
    l.normal = r.vec3("normal", l.normal, -1e6, 1e6);
    if (!(glm::length(l.normal) > 0.0)) fail(r.key("normal"), "must not be the zero vector");
    l.normal = glm::normalize(l.normal);
    l.tangent = r.vec3("tangent", l.tangent, -1e6, 1e6);
    if (rectangle && !(glm::length(glm::cross(l.normal, l.tangent)) > 1e-6 * glm::length(l.tangent)))
        fail(r.key("tangent"), "must not be parallel to the normal");
    l.width = r.number("width", l.width, 0.0, kMaxDistance);
    if (!(l.width > 0.0)) fail(r.key("width"), "must be a positive number");
    l.height = r.number("height", l.height, 0.0, kMaxDistance);
    if (!(l.height > 0.0)) fail(r.key("height"), "must be a positive number");
    l.radius = r.number("radius", l.radius, 0.0, kMaxDistance);
    if (!(l.radius > 0.0)) fail(r.key("radius"), "must be a positive number");
    l.color = r.vec3("color", l.color, 0.0, 1e6, "3 non-negative numbers");
    // Power: Frostbite 4.7.1's two units, exactly one (its absence told after the unknown keys).
    const bool hasLumens = r.has("lumens"), hasLuminance = r.has("luminance");
    if (hasLumens && hasLuminance) fail(r.key("luminance"), "and lumens are both given: give one");
    for (const char* k : {"lumens", "luminance"})
        if (r.has(k)) {
            const double value = r.number(k, 0.0, 0.0, 1e15);
            if (!(value > 0.0)) fail(r.key(k), "must be a positive number");
            (std::string(k) == "lumens" ? l.lumens : l.luminance) = value;
        }
    r.finish();
    if (!hasLumens && !hasLuminance) fail(r.key("lumens"), "or luminance (cd/m2) is required");
    return l;
}

SceneOutputs outputs(const json& v, const fs::path& base, const Fail& fail) {
    ObjectReader r(v, "outputs", fail);
    SceneOutputs o;
    const std::string directory = r.stringValue(r.required("directory"), r.key("directory"));
    if (directory.empty()) fail(r.key("directory"), "must name a directory");
    if (hasControlBytes(directory))
        fail(r.key("directory"),
             quotedForMessage(directory) + " holds control bytes, which no file name may");
    if (leavesItsDirectory(directory))
        fail(r.key("directory"), valueForMessage(directory) +
                                     " leaves the scene's directory: a relative output directory must stay "
                                     "inside it (an absolute path may name any)");
    o.directory = resolve(directory, base);
    o.directoryAbsolute = fs::path(directory).is_absolute();
    o.ktx2Format = r.choice("ktx2Format", "rgba16f", kKtx2FormatNames);
    o.profile = r.choice("profile", "standard", kCubeProfileNames);
    o.quality = r.choice("quality", "production", {"draft", "production", "reference"});
    o.faceSize = r.integer("faceSize", 256, 1, limits::kMaxFaceSize);
    if (!isPowerOfTwo(o.faceSize)) fail(r.key("faceSize"), "must be a power of two");
    o.probeFaceSize = r.integer("probeFaceSize", o.faceSize, 1, limits::kMaxFaceSize);
    if (!isPowerOfTwo(o.probeFaceSize)) fail(r.key("probeFaceSize"), "must be a power of two");
    o.dfgSize = r.integer("dfgSize", 128, 1, 1024);
    o.mipMapping = r.choice("mipMapping", "frostbite", {kMipMappingNames.begin(), kMipMappingNames.end()});
    o.runtimeProfile = r.string("runtimeProfile", "");
    o.irradianceCube = r.boolean("irradianceCube", false);
    o.irradianceFaceSize = r.integer("irradianceFaceSize", 32, 1, 1024);
    if (!isPowerOfTwo(o.irradianceFaceSize)) fail(r.key("irradianceFaceSize"), "must be a power of two");
    o.clampToFormat = r.boolean("clampToFormat", false);
    o.gltf = optionalOutput<SceneGltfOutput>(r, "gltf", fail, [&](ObjectReader& g) {
        SceneGltfOutput out;
        out.file = outputFileName(g, "file", out.file, ".gltf", fail);
        out.minFaceSize = g.integer("minFaceSize", out.minFaceSize, 1, limits::kMaxFaceSize);
        if (!isPowerOfTwo(out.minFaceSize)) fail(g.key("minFaceSize"), "must be a power of two");
        return out;
    });
    o.preview = optionalOutput<ScenePreviewOutput>(r, "preview", fail, [&](ObjectReader& p) {
        ScenePreviewOutput out;
        out.file = outputFileName(p, "file", out.file, ".png", fail);
        out.sphereSize = p.integer("sphereSize", out.sphereSize, 8, 512);
        out.exposure = p.number("exposure", out.exposure, -kMaxExposureStops, kMaxExposureStops);
        return out;
    });
    r.finish();
    return o;
}

} // namespace

const char* sceneCalibrationName(SceneCalibration source) {
    switch (source) {
    case SceneCalibration::Scale:
        return "scale";
    case SceneCalibration::Ev100:
        return "ev100";
    case SceneCalibration::Illuminance:
        return "illuminance";
    case SceneCalibration::SunIlluminance:
        return "sunIlluminance";
    case SceneCalibration::SkyLuminance:
        return "skyLuminance";
    case SceneCalibration::Radiometric:
        return "radiometric";
    default:
        return "none";
    }
}

Scene parseScene(std::string_view text, const std::string& name, const fs::path& baseDirectory) {
    const Fail fail(name);
    json doc;
    try {
        doc = json::parse(text.begin(), text.end());
    } catch (const json::exception& e) {
        fail("", std::string("not valid JSON: ") + e.what());
    }
    try {
        ObjectReader r(doc, "", fail);
        Scene scene;
        scene.name = name;
        r.string("$schema", ""); // editors' schema hint, ignored
        scene.environment = environment(r.required("environment"), baseDirectory, fail);
        if (const json* list = r.take("probes")) {
            if (!list->is_array()) fail("probes", std::string("must be an array, not ") + typeName(*list));
            std::set<std::string> names;
            for (std::size_t i = 0; i < list->size(); ++i) {
                const std::string path = "probes[" + std::to_string(i) + "]";
                scene.probes.push_back(probe((*list)[i], path, baseDirectory, fail));
                if (!names.insert(scene.probes.back().name).second)
                    fail(path + ".name",
                         valueForMessage(scene.probes.back().name) + " is used by an earlier probe");
            }
        }
        if (const json* list = r.take("lights")) {
            if (!list->is_array()) fail("lights", std::string("must be an array, not ") + typeName(*list));
            std::set<std::string> names;
            for (std::size_t i = 0; i < list->size(); ++i) {
                const std::string path = "lights[" + std::to_string(i) + "]";
                scene.lights.push_back(light((*list)[i], path, baseDirectory, fail));
                if (!names.insert(scene.lights.back().name).second)
                    fail(path + ".name",
                         valueForMessage(scene.lights.back().name) + " is used by an earlier light");
            }
        }
        if (const json* m = r.take("materials")) scene.materials = materials(*m, fail);
        scene.outputs = outputs(r.required("outputs"), baseDirectory, fail);
        r.finish();
        return scene;
    } catch (const json::exception& e) { // a conversion the checks above missed: still one clean line
        fail("", std::string("unreadable value: ") + e.what());
    }
}

Scene loadSceneFile(const fs::path& path) {
    const std::string text = readInputFile(path, limits::kMaxDocumentBytes, "scene file");
    return parseScene(text, printableForMessage(path.string()),
                      path.parent_path().empty() ? fs::path(".") : path.parent_path());
}

} // namespace ibl
