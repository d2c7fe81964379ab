// iblbake batch MANIFEST in the engine: the library's batch run, baking stale items with bakeStaleScene.
#include "batch_options.h"
#include "commands.h"

#include <iblbake/baker/bake_scene.h>

#include <memory>

namespace ibl::cli {

Action addBatchCommand(CLI::App& app) {
    auto o = std::make_shared<BatchCommandOptions>();
    addBatchSubcommand(app, *o);
    return
        [o] { return runBatchCommand(*o, loadBatchManifest(o->manifest), chooseShard(*o), bakeStaleScene); };
}

} // namespace ibl::cli
