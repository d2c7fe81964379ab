// The iblbake.diffuse document (iblbake/baker/products.h).
#include "iblbake/baker/products.h"
#include "iblbake/scene/json_vec3.h"

namespace ibl {

namespace {

using nlohmann::json;

json coefficients(const ShRgb& sh) {
    json a = json::array();
    for (const glm::dvec3& c : sh)
        a.push_back(vec3Json(c));
    return a;
}

const char* windowMeaning(ShWindow window) {
    switch (window) {
    case ShWindow::Sloan:
        return "lambda: w_l = 1/(1+lambda l^2 (l+1)^2)";
    case ShWindow::Hanning:
        return "width w in bands: w_l = (1+cos(pi l/w))/2 for l < w, else 0";
    case ShWindow::Lanczos:
        return "width w in bands: w_l = sin(pi l/w)/(pi l/w) for l < w, else 0";
    default:
        return "no window";
    }
}

const char* kIrradianceConvention =
    "pre-convolved with the clamped cosine (A_l = pi, 2pi/3, pi/4) and pre-scaled by the basis constants "
    "k_i: c_i = A_l k_i L_i. Filament's irradianceSH(n) = c0 + c1*n.y + c2*n.z + c3*n.x + c4*n.y*n.x + "
    "c5*n.y*n.z + c6*(3*n.z*n.z-1) + c7*n.z*n.x + c8*(n.x*n.x-n.y*n.y) returns the irradiance "
    "E(n) = integral L(l) max(0, n.l) dl (no 1/pi folded in); multiply by albedo/pi for Lambert radiance";
const char* kIrradianceOverPiConvention =
    "irradiance / pi (the Lambert 1/pi folded in, Filament cmgen's convention): irradianceSH(n) returns "
    "E(n)/pi, the cosine-weighted mean radiance, which is what the irradiance cube stores; multiply by "
    "albedo for Lambert radiance";
const char* kRadianceConvention =
    "L_i = integral L(w) Y_i(w) dw over every source texel (centre direction, exact solid angle, fp64 "
    "sums), standard orthonormal real SH; evaluate as sum L_i Y_i(w)";

// The products' calibration key/values without prefix, the light as JSON rather than its one-line text.
json calibrationObject(const CalibrationRecord& record, const std::optional<DiskLight>& sun) {
    json out = json::object();
    for (const auto& [key, value] : calibrationKeyValues(record, sun, ""))
        out[key] = value;
    if (sun) out["sunLight"] = json::parse(out["sunLight"].get<std::string>());
    return out;
}

} // namespace

json diffuseDocument(const DiffuseSH& sh, const std::string& requestedWindow, const std::string& colorSpace,
                     const DiffuseSource& source, const CalibrationRecord& record,
                     const std::optional<DiskLight>& sun) {
    const ShWindowResult& w = sh.window;
    const json basis =
        json::array({"(0,0) 0.282095", "(1,-1) 0.488603*y", "(1,0) 0.488603*z", "(1,1) 0.488603*x",
                     "(2,-2) 1.092548*x*y", "(2,-1) 1.092548*y*z", "(2,0) 0.315392*(3*z*z-1)",
                     "(2,1) 1.092548*x*z", "(2,2) 0.546274*(x*x-y*y)"});
    json sourceObject = {{"file", source.file},
                         {"width", source.width},
                         {"height", source.height},
                         {"layout", source.layout},
                         {"inputColorSpace", source.inputColorSpace},
                         {"faceSize", source.faceSize},
                         {"rotateDegrees", source.rotateDegrees}};
    addLatLongPixels(sourceObject, source.latLongPixels);
    return {{"schema", "iblbake.diffuse"},
            {"schemaVersion", 1},
            {"generator", "iblbake " IBLBAKE_VERSION},
            {"source", sourceObject},
            {"colorSpace", colorSpace},
            {"units", record.absolute() ? "cd/m2 (luminance); irradiance in lux"
                                        : "relative (input values, uncalibrated)"},
            {"calibration", calibrationObject(record, sun)},
            {"directions", "right-handed, +Y up; (x, y, z) of a unit direction as in DESIGN.md"},
            {"sh",
             {{"order", 2},
              {"coefficientCount", 9},
              {"basis", "real spherical harmonics, standard (orthonormal) normalization"},
              {"basisOrder", basis},
              {"clampedCosineFactors", {3.14159265358979323846, 2.0943951023931955, 0.78539816339744831}},
              {"window",
               {{"name", shWindowName(w.window)},
                {"parameter", w.parameter},
                {"parameterMeaning", windowMeaning(w.window)},
                {"requested", requestedWindow},
                {"searched", w.searched},
                {"bandFactors", {w.factors[0], w.factors[1], w.factors[2]}},
                {"appliedTo", "radiance, irradiance and irradianceOverPi (not radianceUnwindowed)"}}},
              {"minIrradiance",
               {{"before", vec3Json(w.minBefore)},
                {"after", vec3Json(w.minAfter)},
                {"mean", vec3Json(w.meanIrradiance)},
                {"meaning", "minimum over the whole sphere of E(n) reconstructed from the SH, per channel, "
                            "without and with the window; mean = average of E over the sphere"}}},
              {"radianceUnwindowed", coefficients(sh.radianceRaw)},
              {"radiance", coefficients(sh.radiance)},
              {"radianceConvention", kRadianceConvention},
              {"irradiance", coefficients(sh.irradiance)},
              {"irradianceConvention", kIrradianceConvention},
              {"irradianceOverPi", coefficients(sh.irradianceOverPi)},
              {"irradianceOverPiConvention", kIrradianceOverPiConvention}}}};
}

} // namespace ibl
