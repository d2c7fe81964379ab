// Batch manifests (batch.h, docs/batch.md "Batch"): validated like scene files, every error one line naming
// the manifest and the key path; unknown keys are errors.
#include "iblbake/batch/batch.h"
#include "iblbake/core/numeric.h"

#include "iblbake/core/error.h"
#include "iblbake/core/input_file.h"
#include "iblbake/core/limits.h"
#include "iblbake/core/output_path.h"

#include <nlohmann/json.hpp>

#include <cctype>
#include <map>
#include <set>

namespace ibl {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

fs::path resolve(const std::string& path, const fs::path& base) {
    const fs::path p(path);
    return p.is_absolute() ? p : base / p;
}

class ItemReader {
  public:
    ItemReader(const std::string& name, const std::string& keyPath) : name_(name), keyPath_(keyPath) {}

    [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
        throw Error(name_ + ": " + keyPath_ + (key.empty() ? "" : "." + key) + ": " + problem);
    }
    std::string string(const json& item, const char* key) const {
        const json& v = item.at(key);
        if (!v.is_string() || v.get<std::string>().empty()) fail(key, "must be a non-empty string");
        return v.get<std::string>();
    }
    // A file or directory name: control bytes (a NUL would cut it short where the system reads it) refused.
    std::string path(const json& item, const char* key) const {
        const std::string text = string(item, key);
        if (hasControlBytes(text))
            fail(key, quotedForMessage(text) + " holds control bytes, which no file name may");
        return text;
    }

  private:
    const std::string& name_;
    std::string keyPath_;
};

// An item id: it names the item in the progress lines, the summary and a scheduler's logs.
bool validId(const std::string& id) {
    if (id.empty() || id.size() > 128 || id == "." || id == "..") return false;
    for (const char ch : id)
        if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '_' && ch != '-' && ch != '.')
            return false;
    return true;
}

BatchItem parseItem(const json& v, std::size_t index, const std::string& name, const fs::path& base) {
    BatchItem item;
    item.index = index;
    item.keyPath = "items[" + std::to_string(index) + "]";
    const ItemReader r(name, item.keyPath);
    if (!v.is_object()) r.fail("", "must be an object with \"scene\" or \"hdri\"");
    const bool scene = v.contains("scene"), hdri = v.contains("hdri");
    if (scene == hdri) r.fail("", "needs exactly one of \"scene\" and \"hdri\"");
    static const std::set<std::string> sceneKeys = {"scene", "id"};
    static const std::set<std::string> hdriKeys = {"hdri", "id", "output", "preset", "faceSize"};
    for (auto it = v.begin(); it != v.end(); ++it)
        if (!(scene ? sceneKeys : hdriKeys).count(it.key()))
            r.fail(printableForMessage(it.key()),
                   scene ? "unknown key (a scene item has \"scene\" and \"id\")"
                         : "unknown key (an HDRI item has hdri, id, output, preset, faceSize)");
    if (scene) {
        const std::string file = r.path(v, "scene");
        item.sceneFile = resolve(file, base);
        item.id = file;
    } else {
        const std::string file = r.path(v, "hdri");
        item.hdri = resolve(file, base);
        item.id = file;
        if (v.contains("output")) {
            const std::string output = r.path(v, "output");
            if (leavesItsDirectory(output))
                r.fail("output",
                       valueForMessage(output) +
                           " leaves the manifest's directory: a relative output must stay inside it "
                           "(an absolute path may name any)");
            item.output = resolve(output, base);
            item.outputAbsolute = fs::path(output).is_absolute();
        } else {
            item.output = base / item.hdri.stem();
        }
        if (v.contains("preset")) {
            item.preset = r.string(v, "preset");
            if (item.preset != "draft" && item.preset != "production" && item.preset != "reference")
                r.fail("preset",
                       valueForMessage(item.preset) + " is not one of draft, production, reference");
        }
        if (v.contains("faceSize")) {
            const json& f = v["faceSize"];
            if (!f.is_number_integer() || !isPowerOfTwo(f.get<int>()) || f.get<int>() > limits::kMaxFaceSize)
                r.fail("faceSize", "must be a power of two up to " + std::to_string(limits::kMaxFaceSize));
            item.faceSize = f.get<int>();
        }
    }
    if (v.contains("id")) {
        item.id = r.string(v, "id");
        if (!validId(item.id))
            r.fail("id", valueForMessage(item.id) + " must be 1 to 128 of A-Z a-z 0-9 _ - . (not . or ..)");
    }
    return item;
}

} // namespace

BatchManifest parseBatchManifest(std::string_view text, const std::string& name, const fs::path& base) {
    json doc;
    try {
        doc = json::parse(text.begin(), text.end());
    } catch (const json::exception& e) {
        throw Error(name + ": not valid JSON: " + e.what());
    }
    // A bare list of items, or {"items": [...]} (with an optional "$schema" editor hint).
    const json* items = &doc;
    if (doc.is_object()) {
        for (auto it = doc.begin(); it != doc.end(); ++it)
            if (it.key() != "items" && it.key() != "$schema")
                throw Error(name + ": " + printableForMessage(it.key()) + ": unknown key");
        if (!doc.contains("items")) throw Error(name + ": items: is required");
        items = &doc["items"];
    }
    if (!items->is_array()) throw Error(name + ": items: must be an array of items");
    BatchManifest manifest{name, {}};
    std::set<std::string> ids;
    std::map<fs::path, std::size_t> outputs; // HDRI items' output -> index: two bakes in one directory clash
    for (std::size_t i = 0; i < items->size(); ++i) {
        manifest.items.push_back(parseItem((*items)[i], i, name, base));
        const BatchItem& item = manifest.items.back();
        if (!item.isScene()) {
            const auto [it, added] = outputs.emplace(item.output.lexically_normal(), i);
            if (!added)
                throw Error(name + ": items[" + std::to_string(i) +
                            "].output: " + printableForMessage(item.output.string()) +
                            " is also the output of items[" + std::to_string(it->second) + "]");
        }
        if (!ids.insert(manifest.items.back().id).second)
            throw Error(name + ": items[" + std::to_string(i) +
                        "].id: " + valueForMessage(manifest.items.back().id) + " is used by an earlier item");
    }
    return manifest;
}

BatchManifest loadBatchManifest(const fs::path& path) {
    const std::string text = readInputFile(path, limits::kMaxDocumentBytes, "batch manifest");
    return parseBatchManifest(text, printableForMessage(path.string()),
                              path.parent_path().empty() ? fs::path(".") : path.parent_path());
}

Scene batchItemScene(const BatchManifest& manifest, const BatchItem& item) {
    if (item.isScene()) return loadSceneFile(item.sceneFile);
    Scene scene;
    scene.name = manifest.name + ": " + item.keyPath;
    scene.environment.files = {item.hdri};
    scene.outputs.directory = item.output;
    scene.outputs.directoryAbsolute = item.outputAbsolute;
    scene.outputs.quality = item.preset;
    scene.outputs.faceSize = item.faceSize;
    scene.outputs.probeFaceSize = item.faceSize;
    return scene;
}

} // namespace ibl
