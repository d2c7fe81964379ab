// What refuses a bake before any work (iblbake/bake_state/bake_state.h outputDirectoryBelowRoot,
// refusalBeforeWork).
#include "iblbake/bake_state/bake_state.h"
#include "iblbake/core/error.h"

namespace ibl {

std::filesystem::path outputDirectoryBelowRoot(const Scene& scene, const OutputRoot& root) {
    const std::string key = scene.name + ": outputs.directory: ";
    if (scene.outputs.directoryAbsolute)
        throw OutputError(key + scene.outputs.directory.string() +
                          " is written as an absolute path, which an output root refuses: name it relative "
                          "to the scene");
    try {
        return root.below(scene.outputs.directory);
    } catch (const OutputError& e) {
        throw OutputError(key + e.what());
    }
}

std::optional<std::string> refusalBeforeWork(const Scene& scene, const Plan& plan,
                                             const BakeOptions& options) {
    if (!options.outputRoot.empty()) try {
            outputDirectoryBelowRoot(scene, OutputRoot(options.outputRoot));
        } catch (const Error& e) {
            return e.what();
        }
    return budgetRefusal(scene, estimatePlan(scene, plan), options.budget);
}

} // namespace ibl
