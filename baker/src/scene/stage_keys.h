// Cache keys of a plan's stages (docs/scenes.md "Cache"): shared by bakeScene and the up-to-date check, so
// that both agree on what "the same inputs" means.
#pragma once

#include "iblbake/bake_state/code_identity.h"
#include "iblbake/scene/scene.h"
#include "iblbake/scene/scene_plan.h"

#include <map>
#include <string>

namespace ibl {

// The content hash of every file the plan reads, by path. Throws ibl::Error "<scene>: <key path>: ..." for
// a file that cannot be read.
std::map<std::string, std::string> hashPlanInputs(const Scene& scene, const Plan& plan);

// Stage id -> key: XXH3-128 of the tool version, the stage kind, the identity of its code (`code`, by kind:
// the sources that decide its bytes, C++ and kernels; this build's by default), its settings, the name and
// content of every file it reads, its dependencies' keys and, for kernel stages, `backend` ("opencl" or
// "cpu": their results may differ in the last bits). Throws ibl::Error for a kind `code` does not name.
std::map<std::string, std::string> planStageKeys(const Plan& plan,
                                                 const std::map<std::string, std::string>& inputHashes,
                                                 const std::string& backend,
                                                 const StageCodeIdentity& code = builtInStageCodeIdentity());

} // namespace ibl
