// iblbake plan SCENE / iblbake bake SCENE: scene-driven bakes (docs/scenes.md "Scenes").
#include "bake_options.h"
#include "commands.h"
#include "plan_command.h"

#include <iblbake/bake_state/console_progress.h>
#include <iblbake/baker/bake_scene.h>
#include <iblbake/core/error.h>
#include <iblbake/scene/scene.h>

#include <memory>

namespace ibl::cli {

Action addPlanCommand(CLI::App& app) {
    auto o = std::make_shared<PlanOptions>();
    addPlanSubcommand(app, *o);
    return [o] { return runPlan(*o); };
}

Action addBakeCommand(CLI::App& app) {
    auto o = std::make_shared<BakeCommandOptions>();
    addBakeSubcommand(app, *o);
    return [o] {
        const Scene scene = o->loadScene();
        ConsoleProgress progress(chooseProgressMode(o->quiet, o->json));
        const BakeSummary summary = bakeScene(scene, o->bakeOptions(), progress);
        if (!summary.ok) throw Error(summary.error);
        return 0;
    };
}

} // namespace ibl::cli
