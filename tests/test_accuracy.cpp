// iblbake accuracy: the quick sweep on a tiny input (report.json contents, the Markdown table), its HTML in
// headless Chromium, and refusals of bad input without a partial report directory.
#include "cli_runner.h"

#include <iblbake/baker/exr_output.h>
#include <iblbake/core/image.h>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <set>

namespace fs = std::filesystem;

namespace {

using ibl::test::freshTempDir;
using ibl::test::lineCount;
using ibl::test::occurrences;
using ibl::test::runCli;

std::string readFile(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

// A 64 x 32 lat-long: sky gradient, dark ground and a bright spot (a compact source the samplers must find).
fs::path writeTinySky(const fs::path& dir) {
    ibl::ImageRGBA img(64, 32);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 64; ++x) {
            float v = y < 16 ? 1.0f - float(y) / 16.0f : 0.1f;
            img.at(x, y) = glm::vec4(0.2f + v, 0.3f + v, 0.5f + v, 1.0f);
        }
    img.at(40, 8) = glm::vec4(500.0f, 400.0f, 300.0f, 1.0f);
    fs::path file = dir / "sky.exr";
    ibl::writeExr(file, img, ibl::ExrOutputOptions{});
    return file;
}

// One quick accuracy run shared by the report tests (a few seconds; two timed runs per setting, the
// fewest that show --repeats reaching the report). Its report directory exists beforehand with a file of the
// user's in it (ExistingDirectoryKeepsOtherFiles; a new directory is tests/test_accuracy_library.cpp's
// ReportsAreWrittenCompleteIntoNewAndExistingDirectories): one sweep instead of two.
class QuickReport : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        dir_ = new fs::path(freshTempDir("accuracy_quick"));
        const fs::path report = *dir_ / "report";
        fs::create_directories(report);
        std::ofstream(report / "notes.txt") << "mine\n";
        run_ = new ibl::test::CliRun(runCli("accuracy " + writeTinySky(*dir_).string() + " -o " +
                                            report.string() + " --quick --repeats 2"));
        entriesAfterRun_ = new std::set<std::string>;
        for (const auto& entry : fs::directory_iterator(*dir_))
            entriesAfterRun_->insert(entry.path().filename().string());
        if (run_->exitCode == 0)
            report_ = new nlohmann::json(nlohmann::json::parse(readFile(report / "report.json")));
    }
    static void TearDownTestSuite() {
        fs::remove_all(*dir_);
        delete dir_;
        delete run_;
        delete report_;
        delete entriesAfterRun_;
    }
    void SetUp() override {
        ASSERT_EQ(run_->exitCode, 0) << run_->err;
        ASSERT_NE(report_, nullptr);
    }
    static const nlohmann::json& stage(const std::string& name) {
        for (const nlohmann::json& s : (*report_)["stages"])
            if (s["name"] == name) return s;
        throw std::runtime_error("no stage " + name);
    }
    static inline fs::path* dir_ = nullptr;
    static inline ibl::test::CliRun* run_ = nullptr;
    static inline nlohmann::json* report_ = nullptr;
    static inline std::set<std::string>* entriesAfterRun_ = nullptr; // of dir_, before any test ran
};

TEST_F(QuickReport, EveryStageHasFiniteNonNegativeErrorsAndPositiveTimes) {
    EXPECT_EQ((*report_)["schema"], "iblbake.accuracy");
    std::set<std::string> names;
    for (const nlohmann::json& s : (*report_)["stages"]) {
        names.insert(s["name"].get<std::string>());
        EXPECT_FALSE(s["reference"].get<std::string>().empty()) << s["name"];
        EXPECT_FALSE(s["metrics"]["error"].get<std::string>().empty()) << s["name"];
        ASSERT_GE(s["settings"].size(), 3u) << s["name"];
        for (const nlohmann::json& setting : s["settings"]) {
            for (const char* key : {"error", "maxError", "energyError"}) {
                double value = setting[key];
                EXPECT_TRUE(std::isfinite(value) && value >= 0.0)
                    << s["name"] << " " << setting["label"] << key;
            }
            EXPECT_GT(setting["timeMs"].get<double>(), 0.0) << setting["label"];
            EXPECT_EQ(setting["timesMs"].size(), 2u) << setting["label"];
        }
    }
    EXPECT_EQ(names, (std::set<std::string>{"dfg", "specular", "specular-production", "sh", "irradiance",
                                            "runtime"}));
    // Every level of the specular chain and every roughness column of the runtime is reported.
    for (const nlohmann::json& setting : stage("specular")["settings"])
        EXPECT_EQ(setting["partErrors"].size(), 4u); // 16 px source: levels 1..4
    for (const nlohmann::json& setting : stage("runtime")["settings"])
        EXPECT_EQ(setting["partErrors"].size(), 3u); // r = 0, 0.5, 1
}

// Errors per sample count at every fixed value of the other knobs, for the summary error and for each
// part (specular level). Hammersley sets of different sizes are not nested, so a count can land worse than
// a smaller one by chance; the smaller the part, the larger that chance. Stated tolerance: a step may at
// most double the error (plus 1e-4 absolute, the fp32 floor of the comparisons) for parts of at least 24
// texels (specular levels of 2 px faces and more, whole DFG and irradiance grids), and the most samples must
// be at least as good as the fewest everywhere. The 1 x 1 specular level holds 6 texels, one QMC realization
// each: on the tiny sky it measured 0.82%, 2.42%, 0.99%, 0.21% at 16, 32, 64, 256 samples, so only its end
// points are compared. A sweep that ignored its sample count, or got worse with it, fails; a wrong
// reference is the stage tests' business (tests/test_specular_hdri.cpp, test_dfg.cpp, test_irradiance.cpp).
struct Curve {
    std::vector<std::pair<double, double>> points; // (samples, error)
    bool stepChecked = true;
};

void expectFalling(const std::string& what, Curve curve) {
    std::sort(curve.points.begin(), curve.points.end());
    ASSERT_GE(curve.points.size(), 3u) << what;
    if (curve.stepChecked) {
        for (std::size_t i = 1; i < curve.points.size(); ++i) {
            EXPECT_LE(curve.points[i].second, 2.0 * curve.points[i - 1].second + 1e-4)
                << what << " at " << curve.points[i].first << " samples";
        }
    }
    EXPECT_LE(curve.points.back().second, curve.points.front().second + 1e-6) << what;
}

void expectFallingWithSamples(const nlohmann::json& stage) {
    std::map<std::string, Curve> curves; // "other knobs [part]" -> curve
    for (const nlohmann::json& setting : stage["settings"]) {
        std::string key = stage["name"].get<std::string>() + ":";
        for (const auto& [name, value] : setting["knobs"].items())
            if (name != "samples") key += " " + name + "=" + value.dump();
        const double samples = setting["knobs"]["samples"].get<double>();
        // A stage with parts reports the worst part as its summary, which inherits the 1 x 1 level's noise;
        // its parts are checked step by step instead.
        curves[key].points.emplace_back(samples, setting["error"].get<double>());
        curves[key].stepChecked = setting["partErrors"].empty();
        for (const nlohmann::json& part : setting["partErrors"]) {
            // Specular parts are "L<m> r=...": level m of a faceSize source has faceSize >> m texels a side.
            const int faceSize = setting["knobs"]["faceSize"].get<int>() >>
                                 std::stoi(part["part"].get<std::string>().substr(1));
            Curve& c = curves[key + " " + part["part"].get<std::string>()];
            c.points.emplace_back(samples, part["error"].get<double>());
            c.stepChecked = 6 * faceSize * faceSize >= 24;
        }
    }
    ASSERT_FALSE(curves.empty());
    for (const auto& [what, curve] : curves)
        expectFalling(what, curve);
}

TEST_F(QuickReport, SpecularDfgAndIrradianceErrorsFallAsSamplesIncrease) {
    expectFallingWithSamples(stage("specular"));
    expectFallingWithSamples(stage("specular-production"));
    expectFallingWithSamples(stage("dfg"));
    expectFallingWithSamples(stage("irradiance"));
}

TEST_F(QuickReport, PresetsAndParetoFrontAreMarked) {
    for (const char* name : {"specular", "specular-production", "irradiance", "runtime"}) {
        std::set<std::string> presets;
        for (const nlohmann::json& setting : stage(name)["settings"])
            if (!setting["preset"].is_null()) presets.insert(setting["preset"].get<std::string>());
        EXPECT_EQ(presets, (std::set<std::string>{"draft", "production", "reference"})) << name;
    }
    for (const nlohmann::json& s : (*report_)["stages"]) {
        // The front is exactly the settings that no other setting beats in both time and error.
        for (const nlohmann::json& a : s["settings"]) {
            bool dominated = false;
            for (const nlohmann::json& b : s["settings"])
                dominated |= b["timeMs"] <= a["timeMs"] && b["error"] <= a["error"] &&
                             (b["timeMs"] < a["timeMs"] || b["error"] < a["error"]);
            EXPECT_EQ(a["pareto"].get<bool>(), !dominated) << s["name"] << " " << a["label"];
        }
    }
}

TEST_F(QuickReport, MarkdownTableListsEveryStageAndThePresets) {
    std::string md = readFile(*dir_ / "report" / "report.md");
    EXPECT_NE(md.find("| stage | setting | time | error vs reference |"), std::string::npos);
    for (const nlohmann::json& s : (*report_)["stages"])
        EXPECT_NE(md.find("| " + s["title"].get<std::string>() + " |"), std::string::npos) << s["name"];
    EXPECT_NE(md.find("(production)**"), std::string::npos);
}

// Chromium's headless binary, or "" when it is not installed.
std::string chromium() {
    for (const char* name : {"chromium", "chromium-browser"})
        if (std::system((std::string("command -v ") + name + " >/dev/null 2>&1").c_str()) == 0) return name;
    return "";
}

std::string runCapture(const std::string& command) {
    std::string out;
    FILE* pipe = ::popen(command.c_str(), "r");
    char buf[4096];
    while (std::size_t n = std::fread(buf, 1, sizeof buf, pipe))
        out.append(buf, n);
    ::pclose(pipe);
    return out;
}

TEST_F(QuickReport, HtmlRendersInHeadlessChromium) {
    const std::string browser = chromium();
    if (browser.empty()) GTEST_SKIP() << "chromium is not installed (.ci/install-deps installs it)";
    const fs::path html = fs::absolute(*dir_ / "report" / "report.html");
    // A profile of its own: parallel tests must not share Chromium's profile lock.
    const std::string common = browser + " --headless --no-sandbox --disable-gpu --user-data-dir=" +
                               (*dir_ / "chromium-profile").string() + " ";
    const std::string dom = runCapture(common + "--dump-dom file://" + html.string() + " 2>/dev/null");
    std::size_t presetCount = 0;
    for (const nlohmann::json& s : (*report_)["stages"])
        for (const nlohmann::json& setting : s["settings"])
            presetCount += !setting["preset"].is_null();
    EXPECT_EQ(occurrences(dom, "<svg class=\"plot\""), (*report_)["stages"].size()) << dom.substr(0, 400);
    EXPECT_EQ(occurrences(dom, "class=\"preset-marker\""), presetCount);
    EXPECT_EQ(occurrences(dom, "class=\"pareto-front\""), (*report_)["stages"].size());

    const fs::path png = *dir_ / "screenshot.png";
    runCapture(common + "--window-size=1000,1200 --screenshot=" + png.string() + " file://" + html.string() +
               " 2>/dev/null");
    auto in = OIIO::ImageInput::open(png.string());
    ASSERT_TRUE(in) << png << " was not written";
    const OIIO::ImageSpec spec = in->spec();
    std::vector<unsigned char> pixels(std::size_t(spec.width) * spec.height * spec.nchannels);
    ASSERT_TRUE(in->read_image(0, 0, 0, -1, OIIO::TypeDesc::UINT8, pixels.data()));
    // Not blank: dark pixels (text, axes) and the orange Pareto front / red preset markers are present.
    std::size_t dark = 0, orange = 0, total = std::size_t(spec.width) * spec.height;
    for (std::size_t i = 0; i < total; ++i) {
        const unsigned char* p = &pixels[i * std::size_t(spec.nchannels)];
        dark += p[0] < 100 && p[1] < 100 && p[2] < 100;
        orange += p[0] > 180 && p[1] < 140 && p[2] < 80;
    }
    std::printf("screenshot %dx%d: %.2f%% dark, %.3f%% orange/red pixels\n", spec.width, spec.height,
                100.0 * dark / total, 100.0 * orange / total);
    EXPECT_GT(dark, total / 200);
    EXPECT_GT(orange, 100u);
}

// A bad input: one line naming the file, non-zero exit, and neither the report directory nor a temporary
// sibling of it.
TEST(AccuracyCli, BadInputLeavesNoReportDirectory) {
    const fs::path dir = freshTempDir("accuracy_bad");
    const fs::path garbage = dir / "garbage.hdr";
    std::ofstream(garbage) << "#?RADIANCE\nthis is not a picture\n";
    for (const fs::path& input : {dir / "missing.exr", garbage}) {
        ibl::test::CliRun run =
            runCli("accuracy " + input.string() + " -o " + (dir / "report").string() + " --quick");
        EXPECT_EQ(run.exitCode, 1) << run.err;
        EXPECT_EQ(lineCount(run.err), 1) << run.err;
        EXPECT_NE(run.err.find(input.filename().string()), std::string::npos) << run.err;
        EXPECT_FALSE(fs::exists(dir / "report"));
    }
    for (const auto& entry : fs::directory_iterator(dir))
        EXPECT_EQ(entry.path().filename().string().find("report"), std::string::npos) << entry.path();
    fs::remove_all(dir);
}

// An existing report directory gets the new reports and keeps the user's other files; no temporary sibling
// of it is left.
TEST_F(QuickReport, ExistingDirectoryKeepsOtherFiles) {
    const fs::path report = *dir_ / "report";
    EXPECT_EQ(readFile(report / "notes.txt"), "mine\n");
    for (const char* name : {"report.json", "report.md", "report.html"})
        EXPECT_GT(fs::file_size(report / name), 100u) << name;
    EXPECT_EQ(*entriesAfterRun_, (std::set<std::string>{"sky.exr", "report"}));
}

} // namespace
