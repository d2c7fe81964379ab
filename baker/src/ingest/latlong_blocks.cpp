// A lat-long read block by block for resampleLatLongBlocks (ingest_internal.h RepairedLatLongBlocks): each
// block decoded when first asked for, then repaired and colour-converted as ingestEnvironment does a whole
// image, so that the cube is the same bit for bit while only a few blocks are held (docs/performance.md
// "Big HDRIs").
#include "ingest_internal.h"

#include <algorithm>
#include <mutex>
#include <utility>

namespace ibl::ingest {

std::uint64_t defaultBlockPixels(int width) {
    return std::max<std::uint64_t>(std::uint64_t(1) << 21, 64 * std::uint64_t(width));
}

RepairedLatLongBlocks::RepairedLatLongBlocks(OpenedImage& image, const glm::dvec3& luminanceWeights,
                                             std::function<RepairCounts(ImageRGBA&)> convertColour,
                                             std::uint64_t blockPixels)
    : image_(image), luminanceWeights_(luminanceWeights), convertColour_(std::move(convertColour)) {
    // Whole chunks: a chunk is decoded whole (image_source.h).
    const ImageHeader& header = image.source->header();
    const std::uint64_t chunk = std::uint64_t(std::max(1, header.rowsPerRead));
    const std::uint64_t rows = std::max<std::uint64_t>(1, (blockPixels + header.width - 1) / header.width);
    blockRows_ = int(std::min<std::uint64_t>(header.height, (rows + chunk - 1) / chunk * chunk));
    const int blocks = (height() + blockRows_ - 1) / blockRows_;
    held_.resize(std::size_t(blocks));
    decoded_.resize(std::size_t(blocks), false);
}

const glm::vec4* RepairedLatLongBlocks::acquire(int block) {
    const int y0 = block * blockRows_, y1 = std::min(height(), y0 + blockRows_);
    ImageRGBA& pixels = held_[std::size_t(block)];
    pixels.width = width();
    pixels.height = y1 - y0;
    if (!spare_.empty()) {
        pixels.pixels = std::move(spare_.back());
        spare_.pop_back();
    }
    pixels.pixels.resize(std::size_t(pixels.width) * std::size_t(pixels.height));
    // The repair (and, without a colour conversion, the luminance) in the pass that writes the pixels, while
    // they are in cache.
    std::mutex merging;
    FiniteRepair repair;
    readRgbaRows(image_, y0, y1, pixels.pixels.data(), strip_, [&](glm::vec4* first, std::size_t count) {
        const FiniteRepair part = repairFinite(first, count, luminanceWeights_);
        const std::lock_guard lock(merging);
        repair.counts = repair.counts + part.counts;
        repair.plusInf += part.plusInf;
        repair.maxLuminance = std::max(repair.maxLuminance, part.maxLuminance);
    });
    if (repair.plusInf > 0) throw NeedsWholeImage{};
    repairs_ = repairs_ + repair.counts;
    if (convertColour_) {
        const RepairCounts converted = convertColour_(pixels);
        if (converted.inf > 0) throw NeedsWholeImage{};
        repairs_ = repairs_ + converted;
        repair.maxLuminance = ingest::maxLuminance(pixels, luminanceWeights_);
    }
    maxLuminance_ = std::max(maxLuminance_, repair.maxLuminance);
    decoded_[std::size_t(block)] = true;
    return pixels.pixels.data();
}

void RepairedLatLongBlocks::release(int block) {
    spare_.push_back(std::move(held_[std::size_t(block)].pixels));
    held_[std::size_t(block)] = {};
}

void RepairedLatLongBlocks::decodeRest() {
    for (std::size_t block = 0; block < decoded_.size(); ++block)
        if (!decoded_[block]) {
            acquire(int(block));
            release(int(block));
        }
}

} // namespace ibl::ingest
