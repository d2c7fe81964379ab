// An image's pixel count from its header alone (plan_budget.cpp): the budget is computed before any pixel is
// decoded, by the front end too, which links no image library.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>

namespace ibl {

struct ImageHeaderSize {
    std::uint64_t width = 0, height = 0;
    bool openExr = false; // an OpenEXR file, whose lat-long the ingest resamples as it decodes
};

// The size from a Radiance (.hdr), OpenEXR (the first part's dataWindow) or PNG (IHDR) header; nothing
// for another format, a file that cannot be opened or a header that does not parse.
std::optional<ImageHeaderSize> imageHeaderSize(const std::filesystem::path& file);
// Its width x height.
std::optional<std::uint64_t> imageHeaderPixels(const std::filesystem::path& file);

} // namespace ibl
