// The README's first command is one scene bake: its line is install, configure, build, then exactly
// `build/cli/iblbake bake data/scenes/park.json`; that bake step, run on the same scene into a temporary
// directory, makes every product (LUT, LD chain, SH, irradiance cube, sun, the local probe, the glTF, the
// labelled preview) and prints a one-screen report with the preview's measured error.
#include "cli_runner.h"
#include "scene_test_support.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <fstream>
#include <set>
#include <sstream>

namespace fs = std::filesystem;
using nlohmann::json;
using namespace ibl::test;

namespace {

const fs::path kSource = IBLBAKE_SOURCE_DIR;

// The commands of the README's first code block, by line.
std::vector<std::string> readmeCommands() {
    std::ifstream in(kSource / "README.md");
    std::vector<std::string> commands;
    bool inBlock = false;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("```", 0) == 0) {
            if (inBlock) break;
            inBlock = true;
        } else if (inBlock) {
            commands.push_back(line);
        }
    }
    return commands;
}

std::vector<std::string> steps(const std::string& command) {
    std::vector<std::string> out;
    for (std::size_t start = 0;;) {
        const std::size_t end = command.find(" && ", start);
        out.push_back(command.substr(start, end - start));
        if (end == std::string::npos) return out;
        start = end + 4;
    }
}

} // namespace

TEST(ReadmeFirstCommand, IsOneSceneBakeThatMakesEveryProduct) {
    const std::vector<std::string> commands = readmeCommands();
    ASSERT_EQ(commands.size(), 2u) << "the README starts with exactly two commands";
    const std::vector<std::string> first = steps(commands[0]);
    ASSERT_EQ(first.size(), 4u) << commands[0];
    EXPECT_EQ(first[0], "bash .ci/install-deps");
    EXPECT_EQ(first[1].rfind("cmake -S . -B build", 0), 0u) << first[1];
    EXPECT_EQ(first[2].rfind("cmake --build build", 0), 0u) << first[2];
    const std::string bake = "build/cli/iblbake bake ";
    ASSERT_EQ(first[3].rfind(bake, 0), 0u) << first[3];
    const fs::path sceneFile = kSource / first[3].substr(bake.size());

    // The same scene, its paths made absolute and its output in a temporary directory.
    json scene = json::parse(readBytes(sceneFile));
    const fs::path base = sceneFile.parent_path();
    const fs::path dir = freshTempDir("readme_first_command");
    scene["environment"]["file"] =
        (base / scene["environment"]["file"].get<std::string>()).lexically_normal().string();
    for (json& probe : scene["probes"])
        probe["capture"] = (base / probe["capture"].get<std::string>()).lexically_normal().string();
    scene["outputs"]["directory"] = (dir / "park").string();
    writeText(dir / "park.json", scene.dump(2));

    const CliRun run = runCli("bake " + (dir / "park.json").string());
    ASSERT_EQ(run.exitCode, 0) << run.err;
    std::cout << run.out; // the report, for the log
    EXPECT_LE(lineCount(run.out), 25) << run.out;
    const json manifest = json::parse(readBytes(dir / "park" / "manifest.json"));
    std::set<std::string> products;
    for (const auto& [name, product] : manifest["products"].items())
        products.insert(name);
    EXPECT_EQ(products, (std::set<std::string>{"dfg", "specular", "diffuse", "irradiance", "sun", "probes",
                                               "gltf", "preview"}));
    EXPECT_EQ(manifest["products"]["probes"].size(), 1u);
    for (const char* line : {"dfg_lut.ktx2", "specular.ktx2", "diffuse.json", "irradiance.ktx2", "sun.json",
                             "probe_pavilion.ktx2", "park.gltf", "preview.png", "manifest.json"})
        EXPECT_NE(run.out.find(line), std::string::npos) << line << " not in the report:\n" << run.out;
    EXPECT_NE(run.out.find("calibration"), std::string::npos) << run.out;
    // The preview's measured error, every column of both rows: a picture's budget (256 samples per
    // strategy), not the accuracy tables' measurement.
    for (const char* row : {"dielectric", "metal"})
        for (const json& e : manifest["products"]["preview"]["error"][row])
            EXPECT_LT(e.get<double>(), 0.15) << row;
    fs::remove_all(dir);
}
