#include "plan_command.h"

#include <iblbake/scene/plan_budget.h>
#include <iblbake/scene/scene.h>
#include <iblbake/scene/scene_plan.h>

#include <cstdio>

namespace ibl::cli {

CLI::App* addPlanSubcommand(CLI::App& app, PlanOptions& o) {
    CLI::App* cmd = app.add_subcommand("plan", "print the stages a scene needs, and why, without baking");
    cmd->add_option("scene", o.scene, "scene file (JSON, docs/scenes.md \"Schema\")")->required();
    cmd->add_flag("--json", o.json, "print the plan as one JSON object");
    return cmd;
}

int runPlan(const PlanOptions& o) {
    const Scene scene = loadSceneFile(o.scene);
    const Plan plan = planScene(scene);
    const PlanBudget budget = estimatePlan(scene, plan);
    if (o.json) {
        nlohmann::json document = planToJson(plan);
        document["budget"] = budgetToJson(budget, {});
        std::printf("%s\n", document.dump(2).c_str());
    } else {
        std::printf("%s%s", planText(scene, plan).c_str(), budgetText(budget, {}).c_str());
    }
    return 0;
}

} // namespace ibl::cli
