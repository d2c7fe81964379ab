// Fuzz target: arbitrary bytes as an environment image file, through the ingest's reader exactly as a bake
// opens one (baker/src/ingest/read_image.cpp: regular-file check, the reader its first bytes pick (OpenEXR,
// Radiance, else the OpenImageIO module; image_source.h) and its header,
// the pixel limit, the layout check on the header, then the pixels strip by strip), an OpenEXR lat-long first
// as the streamed ingest reads it (blocks in the resampling's order, repaired, resampled). The limit is set
// to kMaxPixels here, so the contract is: the file is refused with ibl::Error in one line naming it, or it is
// read as an image of at most kMaxPixels pixels with a layout the ingest can resample. Memory beyond what
// such an image needs (libFuzzer's -rss_limit_mb and -malloc_limit_mb in .ci/fuzz) is a finding, whether our
// code or a library takes it. The bytes go to a file named .exr when they start with OpenEXR's magic number,
// else .hdr (Radiance), as a user's files would be named. Seeds: fuzz/seeds/image_header/, written by
// oiiotool: tiny lat-long, cross and strip images as .hdr (flat and run-length encoded) and .exr (zip, rle,
// tiled piz, an envmap attribute), three of them truncated at half, and a header of each format claiming
// 262661x15105 pixels.
#include "parser_target.h"

#include "ingest_internal.h"

#include <iblbake/core/limits.h>

#include <sanitizer/common_interface_defs.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <unistd.h>

namespace {

constexpr std::uint64_t kMaxPixels = 4096;

std::string fileFor(const std::uint8_t* data, std::size_t size) {
    static const std::string stem = "/tmp/iblbake-fuzz-image-" + std::to_string(::getpid());
    const std::uint8_t exrMagic[4] = {0x76, 0x2f, 0x31, 0x01};
    const bool exr = size >= 4 && std::memcmp(data, exrMagic, 4) == 0;
    return stem + (exr ? ".exr" : ".hdr");
}

// The streamed ingest of an OpenEXR lat-long (ingest.cpp ingestLatLongInBlocks) without its colour
// conversion: blocks of one chunk each, so that reads go top and bottom in the resampling's order, each block
// repaired, then the blocks never read; a +Inf ends it as it sends the ingest to the whole image.
void resampleInBlocks(const std::string& name) {
    ibl::ingest::OpenedImage image = ibl::ingest::openImage(name, [](const ibl::ingest::RawImage& header) {
        ibl::ingest::resolveLayout(header, ibl::EnvLayout::Auto);
    });
    if (!image.source->readsRowsInAnyOrder() ||
        ibl::ingest::resolveLayout(image.raw, ibl::EnvLayout::Auto) != ibl::EnvLayout::LatLong)
        return;
    ibl::ingest::RepairedLatLongBlocks blocks(image, glm::dvec3(0.2126, 0.7152, 0.0722), nullptr,
                                              std::uint64_t(image.raw.pixels.width));
    try {
        ibl::ingest::resampleLatLongBlocks(blocks, 4, ibl::LatLongPixels::Centre, 0.0);
        blocks.decodeRest();
    } catch (const ibl::ingest::NeedsWholeImage&) {
    }
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    ::setenv(ibl::limits::kMaxImagePixelsVariable, std::to_string(kMaxPixels).c_str(), 1);
    // The reader mutes stderr while a library decodes (baker/src/io/muted_stderr.h); a sanitizer report
    // from inside the decoder goes to a copy of the real stderr instead.
    __sanitizer_set_report_fd(reinterpret_cast<void*>(static_cast<std::intptr_t>(::dup(STDERR_FILENO))));
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string file = fileFor(data, size);
    std::ofstream(file, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), size);
    ibl::fuzz::parseOrRefuse(data, size, file, [](auto, const std::string& name) {
        resampleInBlocks(name);
        const ibl::ingest::RawImage image =
            ibl::ingest::readImage(name, [](const ibl::ingest::RawImage& header) {
                ibl::ingest::resolveLayout(header, ibl::EnvLayout::Auto);
            });
        const std::uint64_t pixels = std::uint64_t(image.pixels.width) * std::uint64_t(image.pixels.height);
        if (pixels == 0 || pixels > kMaxPixels || image.pixels.pixels.size() != pixels) {
            std::fprintf(stderr, "read %dx%d with %zu pixels past the limit of %llu\n", image.pixels.width,
                         image.pixels.height, image.pixels.pixels.size(), (unsigned long long)kMaxPixels);
            std::abort();
        }
    });
    std::remove(file.c_str());
    return 0;
}
