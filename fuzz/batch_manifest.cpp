// Fuzz target: the batch-manifest parser on arbitrary text (parseBatchManifest never touches the file
// system; relative paths are only resolved against the base directory), then the shard split every
// machine of a farm computes from it. Seeds: fuzz/seeds/batch/.
#include "parser_target.h"

#include <iblbake/batch/batch.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return ibl::fuzz::parseOrRefuse(data, size, "fuzz.batch.json", [](auto bytes, const std::string& name) {
        const ibl::BatchManifest manifest = ibl::parseBatchManifest(
            std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), name,
            "/nonexistent");
        // Every item in exactly one of three shards, as on a farm of three machines.
        for (const ibl::BatchItem& item : manifest.items) {
            int shards = 0;
            for (int k = 0; k < 3; ++k)
                shards += ibl::inShard(item, ibl::Shard{k, 3, "--shard"});
            if (shards != 1) {
                std::fprintf(stderr, "item %s is in %d of 3 shards\n", item.id.c_str(), shards);
                std::abort();
            }
        }
    });
}
