// iblbake batch MANIFEST in the engine: the batch run of batch_run.h, baking stale items with bakeStaleScene.
#include "batch_run.h"
#include "commands.h"

#include <memory>

namespace ibl::cli {

Action addBatchCommand(CLI::App& app) {
    auto o = std::make_shared<BatchCommandOptions>();
    addBatchSubcommand(app, *o);
    return [o] { return runBatch(*o, loadBatchManifest(o->manifest), chooseShard(*o), bakeStaleScene); };
}

} // namespace ibl::cli
