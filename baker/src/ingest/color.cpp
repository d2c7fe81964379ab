// Colour: which space the input is in (metadata or the user's word) and the OCIO conversion to the
// working space. The config is the shipped data/ocio/config.ocio unless $OCIO names another one.
#include "../io/shipped_file.h"
#include "ingest_internal.h"

#include "iblbake/core/error.h"

#include <OpenColorIO/OpenColorIO.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <mutex>

#if !defined(IBLBAKE_DATA_DIR) || !defined(IBLBAKE_INSTALLED_DATA_DIR)
// The source tree's data/ and an install's, relative to its programs (baker/CMakeLists.txt).
#error "IBLBAKE_DATA_DIR and IBLBAKE_INSTALLED_DATA_DIR must name the directories that hold ocio/config.ocio"
#endif

namespace OCIO = OCIO_NAMESPACE;

namespace ibl::ingest {

namespace {

OCIO::ConstConfigRcPtr config() {
    static std::mutex mutex;
    static std::map<std::string, OCIO::ConstConfigRcPtr> cache; // one per path, so that $OCIO may change
    const std::string path = ocioConfigPath();
    std::lock_guard<std::mutex> lock(mutex);
    auto it = cache.find(path);
    if (it != cache.end()) return it->second;
    try {
        OCIO::ConstConfigRcPtr cfg = OCIO::Config::CreateFromFile(path.c_str());
        cache.emplace(path, cfg);
        return cfg;
    } catch (const OCIO::Exception& e) {
        throw Error(path + ": cannot load the OpenColorIO config: " + e.what());
    }
}

// The config's own name of a colour space given by name or alias, "" if it has none.
std::string canonical(const OCIO::ConstConfigRcPtr& cfg, const std::string& name) {
    if (name.empty()) return {};
    OCIO::ConstColorSpaceRcPtr cs = cfg->getColorSpace(name.c_str());
    return cs ? std::string(cs->getName()) : std::string();
}

// Named sets of EXR chromaticities (red, green, blue, white xy) the shipped config knows.
struct KnownPrimaries {
    const char* space;
    float xy[8];
};
constexpr KnownPrimaries kKnownPrimaries[] = {
    {"lin_rec709", {0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f}},         // ITU-R BT.709
    {"acescg", {0.713f, 0.293f, 0.165f, 0.830f, 0.128f, 0.044f, 0.32168f, 0.33767f}},     // S-2014-004
    {"aces2065-1", {0.7347f, 0.2653f, 0.0f, 1.0f, 0.0001f, -0.077f, 0.32168f, 0.33767f}}, // ST 2065-1
};

std::string spaceOfChromaticities(const std::vector<float>& xy) {
    for (const KnownPrimaries& k : kKnownPrimaries) {
        bool same = true;
        for (int i = 0; i < 8; ++i)
            same = same && std::fabs(xy[std::size_t(i)] - k.xy[i]) < 1e-3f;
        if (same) return k.space;
    }
    return {};
}

} // namespace

std::string ocioConfigPath() {
    const char* env = std::getenv("OCIO");
    if (env && *env) return env;
    static const std::string shipped =
        shippedFile(IBLBAKE_INSTALLED_DATA_DIR "/ocio/config.ocio", IBLBAKE_DATA_DIR "/ocio/config.ocio");
    return shipped;
}

std::string colorSpaceName(const std::string& nameOrAlias) {
    return canonical(config(), nameOrAlias);
}

std::string resolveInputColorSpace(const RawImage& image, const std::string& requested) {
    OCIO::ConstConfigRcPtr cfg = config();
    if (!requested.empty()) {
        std::string name = canonical(cfg, requested);
        if (name.empty())
            throw SettingError("inputColorSpace",
                               "'" + requested + "' is not a colour space of " + ocioConfigPath());
        return name;
    }
    // EXR chromaticities are specific; OIIO's oiio:ColorSpace for float files is usually a generic "Linear".
    const bool hasChromaticities = image.chromaticities.size() == 8 &&
                                   std::any_of(image.chromaticities.begin(), image.chromaticities.end(),
                                               [](float v) { return v != 0.0f; });
    if (hasChromaticities) {
        std::string fromPrimaries = spaceOfChromaticities(image.chromaticities);
        if (fromPrimaries.empty())
            throw SettingError("inputColorSpace",
                               image.file + ": its chromaticities match none of lin_rec709, acescg, "
                                            "aces2065-1; give the input colour space");
        std::string name = canonical(cfg, fromPrimaries);
        if (!name.empty()) return name;
    }
    if (std::string name = canonical(cfg, image.colorSpace); !name.empty()) return name;
    // No usable metadata: integer files are display-encoded (sRGB), float files scene-linear Rec.709.
    std::string fallback = canonical(cfg, image.integerPixels ? "srgb" : "lin_rec709");
    if (fallback.empty())
        throw SettingError("inputColorSpace", image.file + ": cannot tell its colour space and " +
                                                  ocioConfigPath() + " has no '" +
                                                  (image.integerPixels ? "srgb" : "lin_rec709") +
                                                  "'; give the input colour space");
    return fallback;
}

namespace {

// The conversion from -> to, null when it is the identity.
OCIO::ConstCPUProcessorRcPtr colorProcessor(const std::string& from, const std::string& to,
                                            const std::string& file) {
    OCIO::ConstConfigRcPtr cfg = config();
    const std::string src = canonical(cfg, from), dst = canonical(cfg, to);
    if (src.empty()) throw Error(file + ": colour space '" + from + "' is not in " + ocioConfigPath());
    if (dst.empty())
        throw SettingError("workingColorSpace",
                           "working colour space '" + to + "' is not in " + ocioConfigPath());
    if (src == dst) return nullptr;
    OCIO::ConstCPUProcessorRcPtr cpu;
    try {
        cpu = cfg->getProcessor(src.c_str(), dst.c_str())->getDefaultCPUProcessor();
    } catch (const OCIO::Exception& e) {
        throw Error(file + ": cannot convert " + src + " to " + dst + ": " + e.what());
    }
    return cpu->isNoOp() ? nullptr : cpu;
}

} // namespace

bool isIdentityConversion(const std::string& from, const std::string& to, const std::string& file) {
    return !colorProcessor(from, to, file);
}

bool convertColor(ImageRGBA& image, const std::string& from, const std::string& to, const std::string& file) {
    const OCIO::ConstCPUProcessorRcPtr cpu = colorProcessor(from, to, file);
    if (!cpu) return false;
    // OCIO processors are thread-safe; each task converts a band of rows in place (RGBA, alpha kept).
    tbb::parallel_for(tbb::blocked_range<int>(0, image.height, 16), [&](const tbb::blocked_range<int>& rows) {
        float* first = &image.at(0, rows.begin()).x;
        OCIO::PackedImageDesc desc(first, image.width, long(rows.size()), 4);
        cpu->apply(desc);
    });
    return true;
}

RepairCounts convertColorRepaired(ImageRGBA& image, const std::string& from, const std::string& to,
                                  const std::string& file) {
    return convertColor(image, from, to, file) ? sanitize(image) : RepairCounts{};
}

glm::dvec3 luminanceWeights(const std::string& linearSpace) {
    // Y row of the Rec.709 RGB -> XYZ matrix, from the BT.709 primaries and D65 (see config.ocio).
    const glm::dvec3 rec709Y(0.2126390059, 0.7151686788, 0.0721923154);
    OCIO::ConstConfigRcPtr cfg = config();
    const std::string src = canonical(cfg, linearSpace), ref = canonical(cfg, "lin_rec709");
    if (src.empty())
        throw SettingError("workingColorSpace",
                           "working colour space '" + linearSpace + "' is not in " + ocioConfigPath());
    if (ref.empty())
        throw Error(ocioConfigPath() +
                    ": has no lin_rec709 colour space, which luminance is measured against");
    if (src == ref) return rec709Y;
    OCIO::ConstCPUProcessorRcPtr cpu = cfg->getProcessor(src.c_str(), ref.c_str())->getDefaultCPUProcessor();
    // Each primary's luminance is the Y of its Rec.709 image; a linear space needs nothing more.
    glm::dvec3 w;
    float probe[2][3] = {{1.0f, 2.0f, 4.0f}, {2.0f, 4.0f, 8.0f}};
    cpu->applyRGB(probe[0]);
    cpu->applyRGB(probe[1]);
    for (int c = 0; c < 3; ++c)
        if (std::fabs(probe[1][c] - 2.0f * probe[0][c]) > 1e-4f * std::fabs(probe[1][c]) + 1e-6f)
            throw SettingError("workingColorSpace", "working colour space '" + linearSpace +
                                                        "' is not linear; use lin_rec709 or acescg");
    for (int c = 0; c < 3; ++c) {
        float rgb[3] = {0.0f, 0.0f, 0.0f};
        rgb[c] = 1.0f;
        cpu->applyRGB(rgb);
        w[c] = rec709Y.x * rgb[0] + rec709Y.y * rgb[1] + rec709Y.z * rgb[2];
    }
    return w;
}

} // namespace ibl::ingest
