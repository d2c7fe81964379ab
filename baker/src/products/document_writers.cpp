// The writers of the products that are no LD chain (product_writers.h): the irradiance cube, the DFG LUT,
// the diffuse document, the sun's light and the calibrated environment.
#include "iblbake/baker/exr_output.h"
#include "iblbake/baker/product_writers.h"
#include "iblbake/ktx2/atomic_file.h"
#include "iblbake/ktx2/cube_profile.h"

namespace ibl {

namespace fs = std::filesystem;

StoredCube writeIrradianceCubeProduct(OutputSet& outputs, CubeMap cube,
                                      const IrradianceCubeWriteSettings& settings,
                                      const CalibrationRecord& record, const std::optional<DiskLight>& sun,
                                      const fs::path& file) {
    CubeMapChain chain;
    chain.levels.push_back(std::move(cube));
    StoredCube stored;
    stored.storage = chooseProductStorage(chain, settings.format, settings.clampToFormat);
    Ktx2KeyValues keyValues = irradianceKeyValues(settings.methodText, settings.colorSpace, settings.source,
                                                  settings.latLongPixels, record, sun);
    keyValues.emplace_back(kCubeProfileKey, settings.profile);
    outputs.writeFile(file, [&](const fs::path& temporary) {
        stored.stats = writeProductCube(temporary, chain, settings.format, keyValues, stored.storage);
    });
    return stored;
}

void writeDfgLutProduct(OutputSet& outputs, const ImageRGBA& lut, std::uint32_t samples, DfgLutFile kind,
                        const fs::path& file) {
    outputs.writeFile(file, [&](const fs::path& temporary) {
        if (kind == DfgLutFile::Ktx2) {
            writeKtx2Image(temporary, lut, Ktx2Format::RGBA32F, dfgLutMetadata("iblbake.", "row", samples));
            return;
        }
        ExrOutputOptions exr;
        exr.channels = 3;
        exr.pixelType = kind == DfgLutFile::ExrHalf ? PixelType::Half : PixelType::Float;
        exr.attributes = dfgLutMetadata("iblbake:", "scanline", samples);
        exr.attributes.emplace_back("iblbake:version", IBLBAKE_VERSION);
        exr.attributes.emplace_back("Software", "iblbake " IBLBAKE_VERSION);
        writeExr(temporary, lut, exr);
    });
}

void writeDiffuseProduct(OutputSet& outputs, const DiffuseSH& sh, const std::string& requestedWindow,
                         const std::string& colorSpace, const DiffuseSource& source,
                         const CalibrationRecord& record, const std::optional<DiskLight>& sun,
                         const fs::path& file) {
    const nlohmann::json document = diffuseDocument(sh, requestedWindow, colorSpace, source, record, sun);
    outputs.writeFile(file,
                      [&](const fs::path& temporary) { writeFileBytes(temporary, document.dump(2) + '\n'); });
}

std::string writeSunProduct(OutputSet& outputs, const DiskLight& light, bool absolute, const fs::path& file) {
    const std::string text = diskLightToJson(light, absolute);
    outputs.writeFile(file, [&](const fs::path& temporary) { writeFileBytes(temporary, text + '\n'); });
    return text;
}

void writeCalibratedEnvironment(OutputSet& outputs, const CalibratedImage& calibrated, const fs::path& file) {
    const IngestReport& r = calibrated.report;
    const std::string layoutDescription =
        calibrated.latLong
            ? "latlong (DESIGN.md / OpenEXR LatLongMap: +Y first scanline, +Z at the centre, +X at u = 0.25)"
            : "vstrip: faces +X, -X, +Y, -Y, +Z, -Z stacked vertically, OpenGL face orientation";
    ExrOutputOptions exr;
    exr.channels = 3;
    exr.pixelType = PixelType::Float;
    exr.attributes = {{"iblbake:product", "calibrated-environment"},
                      {"iblbake:layout", layoutDescription},
                      {"iblbake:colorSpace", r.workingColorSpace},
                      {"iblbake:source", fs::path(r.file).filename().string()},
                      {"iblbake:version", IBLBAKE_VERSION},
                      {"Software", "iblbake " IBLBAKE_VERSION}};
    for (auto& kv : latLongPixelsKeyValues(r.latLongPixels, "iblbake:"))
        exr.attributes.push_back(std::move(kv));
    // A lat-long output keeps the input's pixel grid: OpenEXR's placement is what the envmap attribute says,
    // so that ingest reads the file back the same way.
    if (calibrated.latLong && r.latLongPixels == LatLongPixels::OpenExr) exr.envmap = ExrEnvmap::LatLong;
    for (auto& kv : calibrationKeyValues(calibrated.record, calibrated.sun, "iblbake:"))
        exr.attributes.push_back(std::move(kv));
    outputs.writeFile(file, [&](const fs::path& temporary) { writeExr(temporary, calibrated.image, exr); });
}

} // namespace ibl
