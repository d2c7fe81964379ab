// A small bake directory made by the CLI as a user would (specular.ktx2, diffuse.json, irradiance.ktx2
// and, with the sun extracted, sun.json), for the engine-output tests.
#pragma once

#include "cli_runner.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace ibl::test {

inline std::string sampleHdri() {
    return std::string(IBLBAKE_SOURCE_DIR) + "/data/rooitou_park_1k.hdr";
}

// Bakes the sample HDRI at 32-texel faces, calibrated to a 100,000-lux sun which is extracted.
// `specularArgs` is added to the specular command (e.g. "--mip-mapping linear"). Fails the test on error.
inline std::filesystem::path makeBakeDir(const std::string& name, const std::string& specularArgs = "") {
    const std::filesystem::path dir = freshTempDir(name);
    const std::string calibration =
        " --size 32 --sun-illuminance 100000 --extract-sun --sun-json " + (dir / "sun.json").string() + " ";
    CliRun specular = runCli("specular " + sampleHdri() + calibration + "--quality draft " + specularArgs +
                             " -o " + (dir / "specular.ktx2").string());
    EXPECT_EQ(specular.exitCode, 0) << specular.err;
    CliRun diffuse =
        runCli("diffuse " + sampleHdri() + calibration + "--irradiance-size 8 --quality draft -o " +
               (dir / "diffuse.json").string() + " --irradiance-cube " + (dir / "irradiance.ktx2").string());
    EXPECT_EQ(diffuse.exitCode, 0) << diffuse.err;
    return dir;
}

} // namespace ibl::test
