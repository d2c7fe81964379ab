// iblbake preview BAKE_DIR: material balls (perceptual roughness 0..1 across, a dielectric and a metal
// row) lit by a bake through the runtime module; with --reference, the brute-force render of the same
// balls against the original environment and a relative-error heat map, as a labelled grid
// (iblbake/baker/material_preview.h). With --lights, the balls lit by each area-light shape and a textured
// card, runtime | fp64 brute force | error (iblbake/baker/light_preview.h).
#include "commands.h"
#include "common_options.h"
#include "input_options.h"

#include <iblbake/baker/light_preview.h>
#include <iblbake/baker/material_preview.h>
#include <iblbake/core/error.h>

#include <cstdio>
#include <filesystem>
#include <optional>

namespace fs = std::filesystem;

namespace ibl::cli {
namespace {

struct PreviewOptions {
    std::string bakeDir;
    std::string output;
    std::string reference;
    bool lights = false;
    std::string card;
    std::string latLongPixels = "auto"; // of the reference, as the bake read it
    float exposure = 0.0f;
    int sphereSize = 96;
    BackendOptions backend;
};

} // namespace

Action addPreviewCommand(CLI::App& app) {
    auto [o, cmd] = addSubcommand<PreviewOptions>(
        app, "preview", "render material balls lit by a bake (and the reference beside it)");
    cmd->add_option("bake", o->bakeDir,
                    "bake directory: manifest.json (iblbake bake), else specular.ktx2, dfg_lut.exr, "
                    "diffuse.json [, sun.json] [, irradiance.ktx2: diffuse from it instead of the SH]; "
                    "not with --lights");
    cmd->add_option("-o,--output", o->output, "output PNG; the linear render goes to the same name with .exr")
        ->required();
    cmd->add_option("--reference", o->reference,
                    "the HDRI the bake came from: add the brute-force render and the error heat map");
    cmd->add_flag("--lights", o->lights,
                  "instead of a bake: the balls lit by a sphere, disk, rectangle and textured rectangle "
                  "light, runtime | fp64 brute force | error");
    cmd->add_option("--card", o->card,
                    "with --lights: the textured light's card (iblbake lightcard); default a built-in one");
    addLatLongPixelsOption(*cmd, o->latLongPixels);
    cmd->add_option("--exposure", o->exposure, "exposure compensation in stops")->capture_default_str();
    cmd->add_option("--sphere-size", o->sphereSize, "pixels per ball")
        ->capture_default_str()
        ->check(CLI::Range(8, 512));
    o->backend.addTo(*cmd);

    return [o = o] {
        auto start = std::chrono::steady_clock::now();
        if (fs::path(o->output).extension() != ".png")
            throw Error(o->output + ": the preview is written as .png");
        if (o->lights && !(o->bakeDir.empty() && o->reference.empty()))
            throw Error("preview --lights takes no bake directory and no --reference");
        if (!o->lights && !o->card.empty()) throw Error("preview: --card " + o->card + " needs --lights");
        if (!o->lights && o->bakeDir.empty()) throw Error("preview: a bake directory, or --lights");
        std::optional<Executor> executor;
        const auto makeExecutor = [&]() -> const Executor& {
            return executor.emplace(o->backend.makeExecutor());
        };
        const fs::path exrPath = fs::path(o->output).replace_extension(".exr");
        int width = 0, height = 0;
        std::string text;
        if (o->lights) {
            const LightPreview p = renderLightPreviewFile(
                o->card, makeExecutor(), {.sphereSize = o->sphereSize, .exposureEV = o->exposure}, o->output,
                exrPath);
            width = p.width, height = p.height, text = lightPreviewErrorText(p);
        } else {
            const BakeDirectoryPreview p = previewBakeDirectory(
                o->bakeDir, o->reference, parseLatLongPixels(o->latLongPixels), makeExecutor,
                {.sphereSize = o->sphereSize, .exposureEV = o->exposure}, o->output, exrPath);
            width = p.preview.width, height = p.preview.height, text = p.text;
        }
        BackendOptions::storeBuiltKernels(*executor);
        std::printf("wrote   %s (%d x %d) and %s (%s)\n", o->output.c_str(), width, height, exrPath.c_str(),
                    executor->description().c_str());
        std::printf("%s", text.c_str());
        std::printf("time    %.1f ms\n", millisecondsSince(start));
        return 0;
    };
}

} // namespace ibl::cli
