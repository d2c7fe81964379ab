// Options every command that reads an HDRI shares: the input file(s), layout, colour spaces, rotation.
#pragma once

#include <iblbake/baker/ingest.h>

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

    void addTo(CLI::App& command);
    IngestSettings settings(int sourceFaceSize) const;
    std::vector<std::filesystem::path> files() const { return {inputs.begin(), inputs.end()}; }
};

// The two report lines every baking command prints about its input.
void printIngestReport(const IngestReport& report);

} // namespace ibl::cli
