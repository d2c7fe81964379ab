// Batch / farm bakes (docs/batch.md "Batch"): a batch manifest lists items (scene files, or HDRIs baked with
// a default scene built in memory); a shard K/N of a build farm takes the items whose index i in the manifest
// has i mod N = K - 1, a pure function of the item's identity, so every item belongs to exactly one shard
// whichever machine reads the manifest. Parsing is pure; errors are ibl::Error "<name>: <key path>: ...".
#pragma once

#include "iblbake/scene/scene.h"

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ibl {

struct BatchItem {
    std::size_t index = 0;           // position in the manifest's item list: decides the shard
    std::string id;                  // unique; default: the scene or HDRI path as written
    std::string keyPath;             // "items[3]", for messages
    std::filesystem::path sceneFile; // a scene item
    // An HDRI item: baked as the default scene (specular, Lambert diffuse, no probes, relative units).
    std::filesystem::path hdri;
    std::filesystem::path output;      // default: <manifest dir>/<HDRI file stem>
    bool outputAbsolute = false;       // written as an absolute path (refused below an output root)
    std::string preset = "production"; // draft, production, reference (outputs.quality)
    int faceSize = 256;                // outputs.faceSize
    bool isScene() const { return !sceneFile.empty(); }
};

struct BatchManifest {
    std::string name; // the manifest file as the user named it
    std::vector<BatchItem> items;
};

// Relative paths resolve against baseDirectory (not touched).
BatchManifest parseBatchManifest(std::string_view text, const std::string& name,
                                 const std::filesystem::path& baseDirectory);
BatchManifest loadBatchManifest(const std::filesystem::path& path); // throws ibl::Error when unreadable

// The item's scene: its scene file loaded (throws ibl::Error naming the file and key path), or the HDRI
// item's default scene.
Scene batchItemScene(const BatchManifest& manifest, const BatchItem& item);

struct Shard {
    int index = 0; // 0-based
    int count = 1;
    std::string source = "none"; // "--shard", "SLURM_ARRAY_TASK_ID", "JOB_COMPLETION_INDEX" or "none"
};

bool inShard(const BatchItem& item, const Shard& shard); // item.index mod count == index

// "K/N", 1 <= K <= N. Throws ibl::Error "--shard: ..." otherwise.
Shard parseShard(const std::string& text);

// The shard a scheduler's job-array variables name (docs/batch.md "Batch"), or nullopt when none is set:
// Slurm: SLURM_ARRAY_TASK_ID minus SLURM_ARRAY_TASK_MIN (0 when unset) out of SLURM_ARRAY_TASK_COUNT, or
// SLURM_ARRAY_TASK_MAX - MIN + 1; Kubernetes indexed jobs: JOB_COMPLETION_INDEX (0-based) out of
// `countOverride` (--shard-count), else IBLBAKE_SHARD_COUNT. `env` looks a variable up (nullptr: unset);
// throws ibl::Error naming the variable when the values are not a valid shard.
std::optional<Shard> shardFromEnvironment(const std::function<const char*(const char*)>& env,
                                          std::optional<int> countOverride);

} // namespace ibl
