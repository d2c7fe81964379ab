// Options every command that reads an HDRI shares: the input file(s), layout, colour spaces, rotation,
// lat-long pixel placement.
#pragma once

#include "commands.h"

#include <iblbake/baker/ingest.h>
#include <iblbake/baker/inspect.h>

#include <CLI/CLI.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace ibl::cli {

struct InputOptions {
    std::vector<std::string> inputs;
    std::string layout = "auto";
    std::string inputColorSpace;
    std::string workingColorSpace = "lin_rec709";
    float rotateDegrees = 0.0f;
    std::string latLongPixels = "auto";

    void addTo(CLI::App& command);
    IngestSettings settings(int sourceFaceSize) const;
    std::vector<std::filesystem::path> files() const { return {inputs.begin(), inputs.end()}; }
};

// The input of the commands that read one HDRI and measure it (calibrate, inspect): the file, the source
// cube's face size (0: from the input), layout, input colour space, lat-long pixel placement.
struct OneInputOptions {
    std::string input;
    int size = 0;
    std::string layout = "auto";
    std::string inputColorSpace;
    std::string latLongPixels = "auto";

    void addTo(CLI::App& command, const char* sizeHelp);
    IngestSettings settings() const;
};

// A subcommand that reads HDRIs (options.input: InputOptions) and writes options.output (-o, required).
template <class Options>
std::pair<std::shared_ptr<Options>, CLI::App*>
addInputSubcommand(CLI::App& app, const char* name, const char* description, const char* outputHelp) {
    auto [options, command] = addSubcommand<Options>(app, name, description);
    options->input.addTo(*command);
    command->add_option("-o,--output", options->output, outputHelp)->required();
    return {options, command};
}

// --latlong-pixels, for the commands that take the input options one by one (preview, OneInputOptions).
void addLatLongPixelsOption(CLI::App& command, std::string& latLongPixels);

} // namespace ibl::cli
