#include "stage_keys.h"

#include "iblbake/bake_state/content_hash.h"
#include "iblbake/core/error.h"

namespace ibl {

std::map<std::string, std::string> hashPlanInputs(const Scene& scene, const Plan& plan) {
    std::map<std::string, std::string> hashes;
    for (const PlanStage& s : plan.stages)
        for (const PlanInput& in : s.inputs)
            if (!hashes.count(in.file.string())) try {
                    hashes[in.file.string()] = hashFile(in.file);
                } catch (const Error& e) {
                    throw Error(scene.name + ": " + in.keyPath + ": " + e.what());
                }
    return hashes;
}

std::map<std::string, std::string> planStageKeys(const Plan& plan,
                                                 const std::map<std::string, std::string>& inputHashes,
                                                 const std::string& backend, const StageCodeIdentity& code) {
    std::map<std::string, std::string> keys;
    for (const PlanStage& stage : plan.stages) {
        const auto identity = code.find(stage.kind);
        if (identity == code.end())
            throw Error("stage kind " + stage.kind + " has no code identity (cmake/StageCode.cmake)");
        ContentHasher h;
        h.add("iblbake " IBLBAKE_VERSION).add(stage.kind).add(identity->second).add(stage.settings.dump());
        for (const PlanInput& in : stage.inputs) // the name too: products record it (iblbake.source)
            h.add(in.file.filename().string()).add(inputHashes.at(in.file.string()));
        for (const std::string& dependency : stage.dependsOn)
            h.add(keys.at(dependency));
        h.add(stage.usesBackend ? backend : "no-backend");
        keys[stage.id] = h.hex();
    }
    return keys;
}

} // namespace ibl
