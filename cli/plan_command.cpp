#include "plan_command.h"

#include <iblbake/scene/scene.h>
#include <iblbake/scene/scene_plan.h>

#include <cstdio>

namespace ibl::cli {

namespace {

void printPlan(const Scene& scene, const Plan& plan) {
    std::printf("plan    %s -> %s\n", scene.name.c_str(), scene.outputs.directory.string().c_str());
    for (const PlanStage& s : plan.stages) {
        std::printf("run     %-16s %-12s %s\n", s.id.c_str(), s.kind.c_str(), s.reason.c_str());
        std::printf("          settings %s\n", s.settings.dump().c_str());
        for (const PlanInput& in : s.inputs)
            std::printf("          input    %s = %s\n", in.keyPath.c_str(), in.file.string().c_str());
        if (!s.dependsOn.empty()) {
            std::string deps;
            for (const std::string& d : s.dependsOn)
                deps += (deps.empty() ? "" : ", ") + d;
            std::printf("          after    %s\n", deps.c_str());
        }
        for (const std::string& p : s.products)
            std::printf("          product  %s\n", p.c_str());
    }
    for (const SkippedStage& s : plan.skipped)
        std::printf("skip    %-16s %-12s %s\n", s.id.c_str(), s.kind.c_str(), s.reason.c_str());
    for (const std::string& n : plan.notes)
        std::printf("note    %s\n", n.c_str());
    std::printf("last    manifest.json (written after every product)\n");
}

} // namespace

CLI::App* addPlanSubcommand(CLI::App& app, PlanOptions& o) {
    CLI::App* cmd = app.add_subcommand("plan", "print the stages a scene needs, and why, without baking");
    cmd->add_option("scene", o.scene, "scene file (JSON, docs/scenes.md \"Schema\")")->required();
    cmd->add_flag("--json", o.json, "print the plan as one JSON object");
    return cmd;
}

int runPlan(const PlanOptions& o) {
    const Scene scene = loadSceneFile(o.scene);
    const Plan plan = planScene(scene);
    if (o.json)
        std::printf("%s\n", planToJson(plan).dump(2).c_str());
    else
        printPlan(scene, plan);
    return 0;
}

} // namespace ibl::cli
