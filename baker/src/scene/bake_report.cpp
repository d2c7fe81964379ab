// The bake's report (bake_state.h addManifestReport): each product of manifest.json with its path, size
// and what it holds, the calibration in one line, the preview's measured error and the warnings. Read back
// from the manifest, so that a bake found up to date (cli/front_end.cpp) reports the same as one that ran.
#include "iblbake/bake_state/bake_state.h"
#include "iblbake/core/numeric.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>

namespace ibl {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string format(const char* pattern, auto... values) {
    char text[256];
    std::snprintf(text, sizeof text, pattern, values...);
    return text;
}

std::string ldChain(const json& p) {
    return format("LD cube chain %s, %d px, %d levels (%s)", p.at("format").get<std::string>().c_str(),
                  p.at("faceSize").get<int>(), p.at("levels").get<int>(),
                  p.at("roughnessMapping").get<std::string>().c_str());
}

// A local probe's chain, its visibility and the alpha values its ingest repaired (absent in older manifests).
std::string localProbe(const json& p) {
    std::string text = ldChain(p);
    if (p.contains("visibility")) text += ", visibility in A (premultiplied)";
    if (p.contains("alphaRepaired")) {
        const json& r = p["alphaRepaired"];
        text += format(", alpha repaired: %llu NaN, %llu negative, %llu over 1",
                       (unsigned long long)r.at("nan").get<std::uint64_t>(),
                       (unsigned long long)r.at("negative").get<std::uint64_t>(),
                       (unsigned long long)r.at("overOne").get<std::uint64_t>());
    }
    return text;
}

std::string describe(const std::string& name, const json& p, const std::string& units) {
    if (name == "dfg")
        return format("DFG LUT %dx%d %s, %d samples", p.at("size").get<int>(), p.at("size").get<int>(),
                      p.at("format").get<std::string>().c_str(), p.at("samples").get<int>());
    if (name == "specular") return ldChain(p);
    if (name == "diffuse")
        return "L2 SH irradiance, 9 RGB coefficients, window: " +
               p.at("sh").at("window").at("name").get<std::string>();
    if (name == "irradiance")
        return format("irradiance cube %s, %d px (E/pi)", p.at("format").get<std::string>().c_str(),
                      p.at("faceSize").get<int>());
    if (name == "sun") {
        const json& l = p.at("light");
        const json& d = l.at("direction");
        return format("disk light %.6g %s, radius %.2f deg, toward (%.2f, %.2f, %.2f)",
                      l.at("illuminance").get<double>(), units == "cd/m2" ? "lux" : "(relative)",
                      l.at("angularRadius").get<double>() / kDegree, d[0].get<double>(), d[1].get<double>(),
                      d[2].get<double>());
    }
    if (name == "gltf")
        return format("glTF 2.0 EXT_lights_image_based, %d levels x 6 RGBD PNG from %d px",
                      p.at("levels").get<int>(), p.at("faceSize").get<int>());
    if (name == "preview")
        return format("labelled grid %dx%d PNG, linear panels as EXR", p.at("width").get<int>(),
                      p.at("height").get<int>());
    return p.value("format", "");
}

ProductReport product(const std::string& name, const json& p, const fs::path& dir, std::string description) {
    ProductReport r{name, (dir / p.at("file").get<std::string>()).lexically_normal(), 0, 1,
                    std::move(description)};
    std::error_code ec;
    r.bytes = fs::file_size(r.path, ec);
    if (p.contains("files"))
        for (const json& f : p["files"]) {
            r.bytes += fs::file_size(dir / f.at("file").get<std::string>(), ec);
            ++r.files;
        }
    return r;
}

std::string calibrationLine(const json& m) {
    const json& record = m.at("calibration").at("record");
    const std::string source = record.value("calibration.source", "none");
    std::string line = format("x%.6g (%s", m.at("calibration").at("factor").get<double>(), source.c_str());
    if (record.contains("calibration.quantity"))
        line += ": " + record["calibration.quantity"].get<std::string>() + " " +
                record.value("calibration.measuredBefore", "?") + " -> " +
                record.value("calibration.measuredAfter", "?");
    return line + "), " + m.at("units").get<std::string>() + ", " + m.at("colorSpace").get<std::string>();
}

} // namespace

void addManifestReport(BakeSummary& summary) {
    try {
        std::ifstream in(summary.manifest);
        const json m = json::parse(in);
        const fs::path dir = summary.manifest.parent_path();
        const json& products = m.at("products");
        // The manifest's own order is alphabetical: the report's follows the bake.
        for (const char* name : {"dfg", "specular", "diffuse", "irradiance", "sun"})
            if (products.contains(name))
                summary.report.push_back(
                    product(name, products[name], dir,
                            describe(name, products[name], m.at("units").get<std::string>())));
        for (const json& p : products.at("probes"))
            summary.report.push_back(
                product("probe:" + p.at("name").get<std::string>(), p, dir, "local " + localProbe(p)));
        for (const char* name : {"gltf", "preview"})
            if (products.contains(name))
                summary.report.push_back(
                    product(name, products[name], dir,
                            describe(name, products[name], m.at("units").get<std::string>())));
        ProductReport manifest{"manifest", summary.manifest.lexically_normal(), 0, 1,
                               "every product with its conventions and content hash"};
        std::error_code ec;
        manifest.bytes = fs::file_size(summary.manifest, ec);
        summary.report.push_back(manifest);
        summary.calibration = calibrationLine(m);
        summary.warnings = m.value("warnings", std::vector<std::string>{}); // absent in older manifests
        if (products.contains("preview")) {
            const json& p = products["preview"];
            summary.previewError =
                PreviewErrorReport{p.at("roughness").get<std::vector<double>>(),
                                   p.at("error").at("dielectric").get<std::vector<double>>(),
                                   p.at("error").at("metal").get<std::vector<double>>(),
                                   p.at("referenceErrorEstimate").at("both").get<std::vector<double>>()};
        }
    } catch (const std::exception&) { // json or filesystem errors: no report, the bake itself stands
        summary.report.clear();
        summary.calibration.clear();
        summary.previewError.reset();
        summary.warnings.clear();
    }
}

} // namespace ibl
