// A plan's budget (plan_budget.h). Each stage kind's memory is a small function of its face sizes and input
// pixel counts, derived from what the stage holds at once (comments below) and checked against measured
// peaks (tests/test_plan_budget.cpp, docs/performance.md "Estimates beside measured peaks").
#include "iblbake/scene/plan_budget.h"

#include "iblbake/core/error.h"
#include "iblbake/core/format_text.h"
#include "image_header_size.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <optional>
#include <unistd.h>

namespace ibl {

namespace {

using nlohmann::json;

constexpr std::uint64_t kMiB = 1024 * 1024;
// The engine before its first stage: the program, OpenColorIO, TBB and the backend (PoCL) started; the
// example scene's peak after the DFG stage was 76-87 MB, and HDRI items of 256-1,024-px faces fit
// 77 MB + their specular stage (docs/performance.md "Estimates beside measured peaks").
constexpr std::uint64_t kResidentBaseBytes = 80 * kMiB;
// The material preview's runtime evaluation beyond the products it loads: measured, not derived (the
// example scene's peak rose by 112 MB in that stage, its products being 11 MB of floats).
constexpr std::uint64_t kPreviewEvaluationBytes = 96 * kMiB;
constexpr std::uint64_t kFloatRgbaBytes = 16; // every image in memory is fp32 RGBA

std::uint64_t cubeBytes(std::uint64_t faceSize) {
    return 6 * faceSize * faceSize * kFloatRgbaBytes;
}

// The bordered pyramid (cube_pyramid.h): every level down to 1 px with a 1-texel border on each side.
std::uint64_t pyramidBytes(std::uint64_t faceSize) {
    std::uint64_t bytes = 0;
    for (std::uint64_t n = faceSize; n >= 1; n /= 2)
        bytes += 6 * (n + 2) * (n + 2) * kFloatRgbaBytes;
    return bytes;
}

// An LD bake (specular.cpp bakeChain, LdBake) of an n-px source: the source (which becomes level 0), the
// residual's bordered pyramid, the levels below 0 (a third of the source) and the level in flight (a
// quarter); with the sun kept for level 0, that cube too. A second pyramid's worth is measured, not derived:
// on OpenCL the device's copy (Dispatcher::share); on the CPU backend, which shares the host pyramid, the
// product writer's encoded copy of the chain and the bright split come to about as much. HDRI items of 256,
// 512, 1,024 and 2,048-px faces (CPU backend) peaked at 77 MB + 4.2 x the source cube; this gives 4.25.
std::uint64_t ldBakeBytes(std::uint64_t faceSize, bool withSun) {
    const std::uint64_t cube = cubeBytes(faceSize);
    return cube + 2 * pyramidBytes(faceSize) + cube / 3 + cube / 4 + (withSun ? cube : 0);
}

// Texel-samples of the LD levels 1 .. integratedLevels - 1 (specular.cpp LdBake::startLevel: a level of
// n-px faces takes samplesFor(quality) x clamp(32 / n, 1, 16) samples a texel).
std::uint64_t ldWork(std::uint64_t faceSize, int integratedLevels, std::uint64_t samples) {
    std::uint64_t work = 0;
    for (int m = 1; m < integratedLevels; ++m) {
        const std::uint64_t n = std::max<std::uint64_t>(1, faceSize >> m);
        work += 6 * n * n * samples * std::clamp<std::uint64_t>(32 / n, 1, 16);
    }
    return work;
}

// specular.cpp samplesFor and irradiance.cpp irradianceSamplesFor, by the scene's outputs.quality.
std::uint64_t ldSamples(const std::string& quality) {
    return quality == "draft" ? 32 : quality == "reference" ? 2048 : 256;
}
std::uint64_t irradianceSamples(const std::string& quality) {
    return quality == "draft" ? 128 : quality == "reference" ? 4096 : 512;
}

std::string grouped(std::uint64_t value) {
    const std::string digits = std::to_string(value);
    std::string text;
    for (std::size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0) text += ',';
        text += digits[i];
    }
    return text;
}

std::string facesText(std::uint64_t faceSize) {
    return grouped(faceSize) + "-px faces";
}

// Pixels of the stage's inputs whose keys start with `prefix`; a file whose header says nothing counts as a
// lat-long of 4 x 2 faces of `faceSize`.
std::uint64_t inputPixels(const PlanStage& stage, const std::string& prefix, std::uint64_t faceSize) {
    std::uint64_t pixels = 0;
    for (const PlanInput& in : stage.inputs)
        if (in.keyPath.rfind(prefix, 0) == 0)
            pixels += imageHeaderPixels(in.file).value_or(8 * faceSize * faceSize);
    return pixels;
}

// What the ingest holds of an OpenEXR lat-long it resamples block by block (latlong_blocks.cpp,
// latlong_to_cube.cpp resampleLatLongBlocks), nothing for another input: blocks of max(64, 2 Mi / width) rows
// (at most the image's) as fp32 RGBA, at most kHeldBlocks at once (the slab being resampled and the one
// before it, top and bottom, and the next slab's, decoded meanwhile: 6 measured at 8k and 16k), the decoder's
// fp32 RGB strip of one block, and the computed texels' table (20 bytes a texel: 3 n^2 texels of n-px faces
// with the mirror symmetry alone, all 6 n^2 at an odd face size). It does not grow with the image's height.
std::optional<std::uint64_t> streamedIngestBytes(const PlanStage& stage, std::uint64_t faceSize) {
    constexpr std::uint64_t kHeldBlocks = 8, kTexelTableBytes = 20, kBlockPixels = std::uint64_t(1) << 21;
    if (stage.inputs.size() != 1) return std::nullopt;
    const std::optional<ImageHeaderSize> size = imageHeaderSize(stage.inputs.front().file);
    const std::string layout = stage.settings.value("layout", std::string("auto"));
    if (!size || !size->openExr ||
        !(layout == "latlong" || (layout == "auto" && size->width == 2 * size->height)))
        return std::nullopt;
    const std::uint64_t blockRows =
        std::min(size->height, std::max<std::uint64_t>(64, (kBlockPixels + size->width - 1) / size->width));
    const std::uint64_t blocks = (size->height + blockRows - 1) / blockRows;
    const std::uint64_t blockPixels = blockRows * size->width;
    const std::uint64_t texels = (faceSize % 2 == 0 ? 3 : 6) * faceSize * faceSize;
    return std::min(kHeldBlocks, blocks) * blockPixels * kFloatRgbaBytes + blockPixels * 12 +
           texels * kTexelTableBytes;
}

std::uint64_t setting(const PlanStage& stage, const char* key) {
    return stage.settings.at(key).get<std::uint64_t>();
}

StageEstimate estimateStage(const Scene& scene, const PlanStage& stage) {
    const SceneOutputs& o = scene.outputs;
    const std::uint64_t face = std::uint64_t(o.faceSize);
    StageEstimate e{stage.id, stage.kind, 0, 0, "outputs.faceSize", facesText(face)};
    const std::string& kind = stage.kind;
    if (kind == "dfg-lut") {
        const std::uint64_t size = setting(stage, "size");
        e.memoryBytes = 2 * size * size * kFloatRgbaBytes; // the LUT and its download
        e.work = size * size * setting(stage, "samples");
        e.drivingKey = "outputs.dfgSize";
        e.what = grouped(size) + "-px LUT";
    } else if (kind == "environment") {
        // The decoded source (fp32 RGBA; a Radiance file's RGBE bytes beside it, 4 more a pixel), or the
        // blocks of an OpenEXR lat-long resampled as it is decoded; the cube and its texel geometry table
        // (one cube's size).
        const std::uint64_t pixels = inputPixels(stage, "environment.file", face);
        const std::optional<std::uint64_t> streamed = streamedIngestBytes(stage, face);
        const std::uint64_t sourceBytes = streamed ? *streamed : pixels * (kFloatRgbaBytes + 4);
        e.memoryBytes = sourceBytes + 2 * cubeBytes(face);
        e.work = pixels + 6 * face * face;
        if (sourceBytes > 2 * cubeBytes(face)) {
            e.drivingKey = "environment.file";
            e.what = grouped(pixels) + "-pixel source";
        }
    } else if (kind == "sun-extract" || kind == "sun-in-probe" || kind == "diffuse-sh") {
        e.memoryBytes = 2 * cubeBytes(face); // the cube and its texel geometry (SphereTexels)
        e.work = 6 * face * face;
    } else if (kind == "specular-ld") {
        e.memoryBytes = ldBakeBytes(face, scene.environment.extractSun);
        e.work = ldWork(face, int(setting(stage, "integratedLevels")), ldSamples(o.quality));
        if (!stage.settings.at("roughLayers").empty()) { // 12 cubes of min(32, n) px, one level each
            const std::uint64_t layer = std::min<std::uint64_t>(32, face);
            e.memoryBytes += 12 * cubeBytes(layer);
            e.work +=
                12 * 6 * layer * layer * ldSamples(o.quality) * std::clamp<std::uint64_t>(32 / layer, 1, 16);
        }
    } else if (kind == "probe-ld") {
        // The capture decoded and resampled (as the environment stage), then its LD bake from that cube.
        const std::uint64_t probeFace = setting(stage, "faceSize");
        const std::string key = stage.inputs.empty() ? "probes" : stage.inputs.front().keyPath;
        const std::uint64_t pixels = inputPixels(stage, key.substr(0, key.find('.')), probeFace);
        const std::uint64_t capture = pixels * (kFloatRgbaBytes + 4);
        e.memoryBytes = capture + cubeBytes(probeFace) + ldBakeBytes(probeFace, false);
        e.work = pixels + ldWork(probeFace, int(setting(stage, "integratedLevels")), ldSamples(o.quality));
        e.drivingKey = "outputs.probeFaceSize";
        e.what = facesText(probeFace);
        if (capture > ldBakeBytes(probeFace, false)) {
            e.drivingKey = key;
            e.what = grouped(pixels) + "-pixel capture";
        }
    } else if (kind == "irradiance-cube") {
        // The environment cube, its pyramid and the irradiance cube (irradiance.cpp bakeIrradianceCube).
        const std::uint64_t size = setting(stage, "faceSize");
        e.memoryBytes = cubeBytes(face) + pyramidBytes(face) + cubeBytes(size);
        e.work = 6 * size * size * irradianceSamples(o.quality);
    } else if (kind == "gltf-export") {
        // The chain read back as floats (4/3 of its level 0) and re-filtered from level 0 as an LD bake.
        e.memoryBytes = cubeBytes(face) * 4 / 3 + ldBakeBytes(face, false);
        e.work = ldWork(face, int(setting(stage, "levels")), ldSamples(o.quality));
    } else if (kind == "preview-reference") {
        // The calibrated cube and its pyramid; the reference's work converges to its target error, so it is
        // not estimated.
        e.memoryBytes = cubeBytes(face) + pyramidBytes(face);
        e.drivingKey = "outputs.preview";
    } else if (kind == "material-preview") {
        // Every distant product and every probe loaded as floats (a chain is 4/3 of its level 0), plus the
        // runtime's evaluation.
        std::uint64_t loaded = cubeBytes(face) * 4 / 3 + cubeBytes(std::uint64_t(o.irradianceFaceSize));
        const std::uint64_t probeFace = std::uint64_t(o.probeFaceSize > 0 ? o.probeFaceSize : o.faceSize);
        loaded += scene.probes.size() * cubeBytes(probeFace) * 4 / 3;
        e.memoryBytes = loaded + kPreviewEvaluationBytes;
        const std::uint64_t ball = std::uint64_t(o.preview ? o.preview->sphereSize : 64);
        e.work = 2 * 11 * ball * ball * (1 + scene.probes.size());
        e.drivingKey = scene.probes.empty() ? "outputs.preview" : "probes";
        e.what = scene.probes.empty()
                     ? facesText(face)
                     : grouped(scene.probes.size()) +
                           (scene.probes.size() == 1 ? " probe of " : " probes of ") + facesText(probeFace);
    } else if (kind == "light-card") {
        const std::uint64_t size = setting(stage, "size"), layers = setting(stage, "layers");
        const std::uint64_t pixels =
            stage.inputs.empty() ? 0 : imageHeaderPixels(stage.inputs.front().file).value_or(size * size);
        e.memoryBytes = pixels * kFloatRgbaBytes + size * size * kFloatRgbaBytes * (layers + 1) * 4 / 3;
        e.work = pixels * (layers + 1);
        e.drivingKey = stage.inputs.empty() ? "lights" : stage.inputs.front().keyPath;
        e.what = grouped(pixels) + "-pixel texture";
    }
    return e;
}

} // namespace

PlanBudget estimatePlan(const Scene& scene, const Plan& plan) {
    PlanBudget budget;
    budget.baseBytes = kResidentBaseBytes;
    for (const PlanStage& stage : plan.stages) {
        budget.stages.push_back(estimateStage(scene, stage));
        const StageEstimate& e = budget.stages.back();
        budget.totalWork += e.work;
        if (e.memoryBytes > budget.stages[budget.peakStage].memoryBytes)
            budget.peakStage = budget.stages.size() - 1;
        if (e.work > budget.stages[budget.workStage].work) budget.workStage = budget.stages.size() - 1;
    }
    budget.peakBytes =
        budget.baseBytes + (budget.stages.empty() ? 0 : budget.stages[budget.peakStage].memoryBytes);
    return budget;
}

std::uint64_t defaultMaxMemoryBytes() {
    const long pages = ::sysconf(_SC_PHYS_PAGES), pageSize = ::sysconf(_SC_PAGE_SIZE);
    if (pages <= 0 || pageSize <= 0) return 0;
    return std::uint64_t(pages) * std::uint64_t(pageSize) / 4 * 3;
}

std::string bytesText(std::uint64_t bytes) {
    const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB"};
    double value = double(bytes);
    int unit = 0;
    while (value >= 1024.0 && unit < 4) {
        value /= 1024.0;
        ++unit;
    }
    if (unit == 0) return grouped(bytes) + " bytes";
    return formatText(value < 100.0 ? "%.1f %s" : "%.0f %s", value, units[unit]);
}

namespace {

std::string workText(std::uint64_t work) {
    return formatText("%.3g", double(work));
}

std::uint64_t memoryLimit(const BudgetLimits& limits) {
    return limits.maxMemoryBytes ? limits.maxMemoryBytes : defaultMaxMemoryBytes();
}

// A number with an optional unit letter (K, M, G, T, powers of `step`), then an optional tail.
std::optional<std::uint64_t> parseScaled(const std::string& text, double step, bool bytes) {
    std::size_t used = 0;
    double value = 0.0;
    try {
        value = std::stod(text, &used);
    } catch (const std::exception&) {
        return std::nullopt;
    }
    std::string unit = text.substr(used);
    double scale = 1.0;
    const std::string letters = "KMGT";
    if (!unit.empty() && letters.find(char(std::toupper(unsigned(unit[0])))) != std::string::npos) {
        scale = std::pow(step, double(letters.find(char(std::toupper(unsigned(unit[0])))) + 1));
        unit.erase(0, 1);
    }
    if (bytes && (unit == "B" || unit == "iB" || (scale == 1.0 && unit == "bytes"))) unit.clear();
    if (!unit.empty() || !std::isfinite(value) || value <= 0.0 || value * scale > 1.8e19) return std::nullopt;
    return std::uint64_t(std::llround(value * scale));
}

} // namespace

std::uint64_t parseByteSize(const std::string& text, const std::string& flag) {
    if (const std::optional<std::uint64_t> bytes = parseScaled(text, 1024.0, true); bytes && *bytes > 0)
        return *bytes;
    throw Error(flag + ": '" + text +
                "' is not a memory size (bytes, or with K, M, G or T: 4G, 512M, 1.5GiB)");
}

std::uint64_t parseWorkCount(const std::string& text, const std::string& flag) {
    if (const std::optional<std::uint64_t> work = parseScaled(text, 1000.0, false); work && *work > 0)
        return *work;
    throw Error(flag + ": '" + text + "' is not a count of texel-samples (2e12, or with K, M, G or T: 500G)");
}

std::optional<std::string> budgetRefusal(const Scene& scene, const PlanBudget& budget,
                                         const BudgetLimits& limits) {
    if (budget.stages.empty()) return std::nullopt;
    const std::uint64_t maxMemory = memoryLimit(limits);
    if (maxMemory > 0 && budget.peakBytes > maxMemory) {
        const StageEstimate& peak = budget.stages[budget.peakStage];
        return scene.name + ": " + peak.drivingKey + ": the plan needs an estimated " +
               bytesText(budget.peakBytes) + " (" + peak.id + ": " + peak.what + "), over --max-memory " +
               bytesText(maxMemory) + (limits.maxMemoryBytes ? "" : " (75% of this machine's memory)");
    }
    if (limits.maxWork > 0 && budget.totalWork > limits.maxWork) {
        // The kind that does most of the work names the key: 2,000 probes' stages, or one large chain.
        std::map<std::string, std::uint64_t> workOfKind;
        std::map<std::string, int> stagesOfKind;
        for (const StageEstimate& e : budget.stages) {
            workOfKind[e.kind] += e.work;
            ++stagesOfKind[e.kind];
        }
        const auto most = std::max_element(workOfKind.begin(), workOfKind.end(),
                                           [](const auto& a, const auto& b) { return a.second < b.second; });
        const StageEstimate* largest = nullptr;
        for (const StageEstimate& e : budget.stages)
            if (e.kind == most->first && (!largest || e.work > largest->work)) largest = &e;
        const int count = stagesOfKind[most->first];
        const std::string what =
            count > 1 ? grouped(std::uint64_t(count)) + " " + most->first + " stages of " + largest->what
                      : largest->id + ": " + largest->what;
        return scene.name + ": " + largest->drivingKey + ": the plan needs an estimated " +
               workText(budget.totalWork) + " texel-samples (" + what + "), over --max-work " +
               workText(limits.maxWork);
    }
    return std::nullopt;
}

std::string budgetText(const PlanBudget& budget, const BudgetLimits& limits) {
    std::string text;
    for (const StageEstimate& e : budget.stages)
        text += formatText("budget  %-16s %10s %10s texel-samples  %s (%s)\n", e.id.c_str(),
                           bytesText(e.memoryBytes).c_str(), e.work ? workText(e.work).c_str() : "-",
                           e.drivingKey.c_str(), e.what.c_str());
    const std::uint64_t maxMemory = memoryLimit(limits);
    const std::string peakStage = budget.stages.empty() ? "no stage" : budget.stages[budget.peakStage].id;
    text += formatText("budget  peak %s (%s resident + %s), --max-memory %s; work %s texel-samples, "
                       "--max-work %s\n",
                       bytesText(budget.peakBytes).c_str(), bytesText(budget.baseBytes).c_str(),
                       peakStage.c_str(), bytesText(maxMemory).c_str(), workText(budget.totalWork).c_str(),
                       limits.maxWork ? workText(limits.maxWork).c_str() : "none");
    return text;
}

json budgetToJson(const PlanBudget& budget, const BudgetLimits& limits) {
    json stages = json::array();
    for (const StageEstimate& e : budget.stages)
        stages.push_back({{"id", e.id},
                          {"memoryBytes", e.memoryBytes},
                          {"work", e.work},
                          {"key", e.drivingKey},
                          {"what", e.what}});
    return {
        {"stages", stages},         {"residentBytes", budget.baseBytes},     {"peakBytes", budget.peakBytes},
        {"work", budget.totalWork}, {"maxMemoryBytes", memoryLimit(limits)}, {"maxWork", limits.maxWork}};
}

} // namespace ibl
