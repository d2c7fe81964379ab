// Options every command that reads an HDRI shares: the input file(s), layout, colour spaces, rotation,
// lat-long pixel placement.
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
    std::string latLongPixels = "auto";

    void addTo(CLI::App& command);
    IngestSettings settings(int sourceFaceSize) const;
    std::vector<std::filesystem::path> files() const { return {inputs.begin(), inputs.end()}; }
};

// --latlong-pixels, for the commands that take the input options one by one (calibrate, inspect).
void addLatLongPixelsOption(CLI::App& command, std::string& latLongPixels);

// The input's layout as the commands print it: "latlong (pixels centre)", "exr-cube".
std::string layoutText(const IngestReport& report);

// The two report lines every baking command prints about its input.
void printIngestReport(const IngestReport& report);

} // namespace ibl::cli
