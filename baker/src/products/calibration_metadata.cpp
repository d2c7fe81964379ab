// Calibration and sun metadata of every product (iblbake/baker/products.h).
#include "iblbake/baker/products.h"
#include "iblbake/core/error.h"

#include <fstream>
#include <iterator>

namespace ibl {

namespace {

using nlohmann::json;

CalibrationSource sourceNamed(const std::string& name) {
    for (int s = int(CalibrationSource::None); s <= int(CalibrationSource::Radiometric); ++s)
        if (name == calibrationSourceName(CalibrationSource(s))) return CalibrationSource(s);
    throw Error("calibration record: source " + quotedForMessage(name) + " is unknown");
}

} // namespace

std::string readText(const std::filesystem::path& path) {
    std::ifstream in(path);
    if (!in) throw Error(path.string() + ": cannot read");
    return {std::istreambuf_iterator<char>(in), {}};
}

std::string sunJson(const DiskLight& light, const CalibrationRecord& record, int indent) {
    return diskLightToJson(light, record.absolute(), indent);
}

Ktx2KeyValues calibrationKeyValues(const CalibrationRecord& record, const std::optional<DiskLight>& sun,
                                   const std::string& prefix) {
    Ktx2KeyValues kv = calibrationMetadata(record, prefix);
    if (sun) {
        kv.emplace_back(prefix + "sun",
                        "extracted as a disk light (Frostbite 4.6), see " + prefix + "sunLight");
        kv.emplace_back(prefix + "sunLight", sunJson(*sun, record, -1));
    } else {
        kv.emplace_back(prefix + "sun", "kept in the environment");
    }
    return kv;
}

json calibrationRecordToJson(const CalibrationRecord& r) {
    return {{"factor", r.factor},
            {"source", calibrationSourceName(r.source)},
            {"sourceValue", r.sourceValue},
            {"quantity", r.quantity},
            {"measuredBefore", r.measuredBefore},
            {"measuredAfter", r.measuredAfter},
            {"upwardIlluminanceBefore", r.upwardIlluminanceBefore},
            {"upwardIlluminanceAfter", r.upwardIlluminanceAfter},
            {"meanLuminanceBefore", r.meanLuminanceBefore},
            {"meanLuminanceAfter", r.meanLuminanceAfter},
            {"sunMeasured", r.sunMeasured},
            {"sunFound", r.sunFound},
            {"sunIlluminanceBefore", r.sunIlluminanceBefore},
            {"sunIlluminanceAfter", r.sunIlluminanceAfter}};
}

CalibrationRecord calibrationRecordFromJson(const json& j) {
    try {
        CalibrationRecord r;
        r.factor = j.at("factor").get<double>();
        r.source = sourceNamed(j.at("source").get<std::string>());
        r.sourceValue = j.at("sourceValue").get<double>();
        r.quantity = j.at("quantity").get<std::string>();
        r.measuredBefore = j.at("measuredBefore").get<double>();
        r.measuredAfter = j.at("measuredAfter").get<double>();
        r.upwardIlluminanceBefore = j.at("upwardIlluminanceBefore").get<double>();
        r.upwardIlluminanceAfter = j.at("upwardIlluminanceAfter").get<double>();
        r.meanLuminanceBefore = j.at("meanLuminanceBefore").get<double>();
        r.meanLuminanceAfter = j.at("meanLuminanceAfter").get<double>();
        r.sunMeasured = j.at("sunMeasured").get<bool>();
        r.sunFound = j.at("sunFound").get<bool>();
        r.sunIlluminanceBefore = j.at("sunIlluminanceBefore").get<double>();
        r.sunIlluminanceAfter = j.at("sunIlluminanceAfter").get<double>();
        return r;
    } catch (const json::exception& e) {
        throw Error(std::string("calibration record: ") + e.what());
    }
}

} // namespace ibl
