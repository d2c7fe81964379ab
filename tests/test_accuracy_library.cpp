// The accuracy sweep in-process (iblbake/accuracy/accuracy.h): the quick plan on a synthetic sky with a
// compact bright spot, every stage measured in report order with finite errors that fall with more samples,
// and the reports (JSON fields, Markdown table, HTML plots) written from the run; tests/test_accuracy.cpp
// runs the same through `iblbake accuracy`.
#include "cli_runner.h"
#include "scene_test_support.h"
#include "test_support.h"

#include <iblbake/accuracy/accuracy.h>
#include <iblbake/baker/sun_in_probe.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>

namespace fs = std::filesystem;

namespace {

// Sky gradient above the horizon, dark ground, and a bright spot of ~8 degrees the samplers must find.
glm::dvec3 sky(const glm::dvec3& direction) {
    if (direction.y < 0.0) return glm::dvec3(0.1);
    glm::dvec3 radiance = glm::dvec3(0.2, 0.3, 0.5) + direction.y;
    if (glm::dot(direction, glm::normalize(glm::dvec3(0.5, 0.6, 0.6))) > 0.99)
        radiance += glm::dvec3(50.0, 40.0, 30.0);
    return radiance;
}

using ibl::test::occurrences;
using ibl::test::readBytes;

constexpr int kRepeats = 2;

// One quick sweep shared by the tests (a few seconds).
class AccuracyLibrary : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        const ibl::SweepPlan plan = ibl::SweepPlan::quick();
        const ibl::AccuracyInput input{"sky", ibl::test::makeCube(plan.sourceFaceSize, sky),
                                       [](int faceSize) { return ibl::test::makeCube(faceSize, sky); }};
        seen_ = new std::vector<std::string>;
        run_ = new ibl::AccuracyRun(
            ibl::runAccuracySweep(plan, input, kRepeats, ibl::test::openclOrCpu(),
                                  [](const ibl::AccuracyStage& stage) { seen_->push_back(stage.name); }));
    }
    static void TearDownTestSuite() {
        delete run_;
        delete seen_;
    }
    static const ibl::AccuracyStage& stage(const std::string& name) {
        for (const ibl::AccuracyStage& s : run_->stages)
            if (s.name == name) return s;
        throw std::runtime_error("no stage " + name);
    }
    static inline ibl::AccuracyRun* run_ = nullptr;
    static inline std::vector<std::string>* seen_ = nullptr;
};

TEST_F(AccuracyLibrary, EveryStageInReportOrderWithFiniteErrorsAndTimes) {
    const std::vector<std::string> order{"dfg", "specular",   "specular-production",
                                         "sh",  "irradiance", "runtime"};
    EXPECT_EQ(*seen_, order); // the callback saw each stage as it was measured
    ASSERT_EQ(run_->stages.size(), order.size());
    EXPECT_TRUE(run_->quick);
    EXPECT_EQ(run_->input, "sky");
    EXPECT_EQ(run_->repeats, kRepeats);
    EXPECT_EQ(run_->sourceFaceSize, 16);
    EXPECT_GT(run_->totalSeconds, 0.0);
    for (const ibl::AccuracyStage& s : run_->stages) {
        EXPECT_FALSE(s.reference.empty()) << s.name;
        EXPECT_FALSE(s.errorMetric.empty()) << s.name;
        ASSERT_GE(s.settings.size(), 3u) << s.name;
        EXPECT_TRUE(std::any_of(s.settings.begin(), s.settings.end(), [](auto& m) { return m.pareto; }))
            << s.name;
        for (const ibl::MeasuredSetting& m : s.settings) {
            for (double value : {m.error, m.maxError, m.energyError})
                EXPECT_TRUE(std::isfinite(value) && value >= 0.0) << s.name << " " << m.label;
            EXPECT_EQ(m.timesMs.size(), std::size_t(kRepeats)) << m.label;
            EXPECT_GT(m.timeMs, 0.0) << m.label;
        }
    }
    for (const ibl::MeasuredSetting& m : stage("specular").settings)
        EXPECT_EQ(m.partErrors.size(), 4u) << m.label; // 16 px source: levels 1..4
    for (const ibl::MeasuredSetting& m : stage("runtime").settings)
        EXPECT_EQ(m.partErrors.size(), 3u) << m.label; // r = 0, 0.5, 1
}

// The sampled stages: at every value of the other knobs, the most samples are no worse than the fewest, and
// better at one value at least (the step-by-step
// tolerance of Hammersley sets that are not nested is tests/test_accuracy.cpp's business).
TEST_F(AccuracyLibrary, MoreSamplesGiveSmallerErrors) {
    for (const char* name : {"dfg", "specular", "specular-production", "irradiance"}) {
        std::map<std::string, std::map<double, double>> curves; // other knobs -> samples -> error
        for (const ibl::MeasuredSetting& m : stage(name).settings) {
            std::string others;
            double samples = 0;
            for (const auto& [knob, value] : m.knobs) {
                if (knob == "samples")
                    samples = std::stod(value);
                else
                    others += knob + "=" + value + " ";
            }
            curves[others][samples] = m.error;
        }
        // No curve rises, and at least one falls: at 16-px faces the specular error no longer depends on
        // the sample count (the bright spot is integrated exactly and its residual is the mean, so what is
        // left is the filtering's own bias: 0.42% at every count, measured).
        bool anyFalls = false;
        for (const auto& [others, curve] : curves) {
            ASSERT_GE(curve.size(), 3u) << name << " " << others;
            EXPECT_LE(curve.rbegin()->second, curve.begin()->second) << name << " " << others;
            anyFalls = anyFalls || curve.rbegin()->second < curve.begin()->second;
        }
        EXPECT_TRUE(anyFalls) << name;
    }
}

TEST_F(AccuracyLibrary, JsonReportHoldsEveryMeasurement) {
    const nlohmann::json report = nlohmann::json::parse(ibl::accuracyJson(*run_));
    EXPECT_EQ(report["schema"], "iblbake.accuracy");
    EXPECT_EQ(report["schemaVersion"], 1);
    EXPECT_EQ(report["input"], "sky");
    EXPECT_EQ(report["quick"], true);
    EXPECT_EQ(report["repeats"], kRepeats);
    EXPECT_EQ(report["backend"], run_->backend);
    for (const char* key : {"generator", "sourceFaceSize", "machine", "totalSeconds", "errorsAre"})
        EXPECT_TRUE(report.contains(key)) << key;
    ASSERT_EQ(report["stages"].size(), run_->stages.size());
    for (std::size_t i = 0; i < run_->stages.size(); ++i) {
        const ibl::AccuracyStage& stage = run_->stages[i];
        const nlohmann::json& s = report["stages"][i];
        EXPECT_EQ(s["name"], stage.name);
        for (const char* metric : {"error", "maxError", "energyError", "time"})
            EXPECT_FALSE(s["metrics"][metric].get<std::string>().empty()) << stage.name << " " << metric;
        ASSERT_EQ(s["settings"].size(), stage.settings.size());
        for (std::size_t j = 0; j < stage.settings.size(); ++j) {
            const ibl::MeasuredSetting& m = stage.settings[j];
            const nlohmann::json& setting = s["settings"][j];
            EXPECT_EQ(setting["label"], m.label);
            EXPECT_EQ(setting["error"].get<double>(), m.error);
            EXPECT_EQ(setting["maxError"].get<double>(), m.maxError);
            EXPECT_EQ(setting["energyError"].get<double>(), m.energyError);
            EXPECT_EQ(setting["timeMs"].get<double>(), m.timeMs);
            EXPECT_EQ(setting["pareto"].get<bool>(), m.pareto);
            EXPECT_EQ(setting["partErrors"].size(), m.partErrors.size());
            EXPECT_EQ(setting["preset"].is_null(), m.preset.empty());
            for (const auto& [knob, value] : m.knobs)
                EXPECT_TRUE(setting["knobs"].contains(knob)) << m.label << " " << knob;
        }
    }
    EXPECT_TRUE(report["stages"][0]["settings"][0]["knobs"]["size"].is_number()); // numeric knobs as numbers
}

TEST_F(AccuracyLibrary, MarkdownAndHtmlShowEveryStage) {
    const std::string md = ibl::accuracyMarkdown(*run_), html = ibl::accuracyHtml(*run_);
    EXPECT_NE(md.find("| stage | setting | time | error vs reference |"), std::string::npos);
    for (const ibl::AccuracyStage& s : run_->stages) {
        EXPECT_NE(md.find("| " + s.title + " |"), std::string::npos) << s.name;
        EXPECT_EQ(occurrences(html, "<svg class=\"plot\" data-stage=\"" + s.name + "\""), 1u) << s.name;
    }
    EXPECT_NE(html.find("(quick sweep)"), std::string::npos);
}

// The reports appear in a new directory together; in an existing one each replaces its old self and the
// directory's other files stay; no temporary sibling is left either way.
TEST_F(AccuracyLibrary, ReportsAreWrittenCompleteIntoNewAndExistingDirectories) {
    const fs::path dir = ibl::test::freshTempDir("accuracy_library");
    for (const fs::path& target : {dir / "new" / "report", dir / "existing"}) {
        if (target.filename() == "existing") {
            fs::create_directories(target);
            std::ofstream(target / "notes.txt") << "kept";
            std::ofstream(target / "report.json") << "old";
        }
        ibl::writeAccuracyReports(target, *run_);
        EXPECT_EQ(readBytes(target / "report.json"), ibl::accuracyJson(*run_)) << target;
        EXPECT_EQ(readBytes(target / "report.md"), ibl::accuracyMarkdown(*run_)) << target;
        EXPECT_EQ(readBytes(target / "report.html"), ibl::accuracyHtml(*run_)) << target;
        for (const auto& entry : fs::directory_iterator(target.parent_path()))
            EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
    }
    EXPECT_EQ(readBytes(dir / "existing" / "notes.txt"), "kept");
    fs::remove_all(dir);
}

} // namespace

// A sun left in the probe: measureSunInProbe finds it, the probe that keeps it errs more on the sphere grid
// than the one that extracts it, and the warning has its stable wording; a sky without a sun gets none.
TEST(SunInProbe, WarnsWithTheErrorItCausesAndTheFix) {
    auto clearSky = [](const glm::dvec3& d) {
        return d.y < 0.0 ? glm::dvec3(0.1) : glm::dvec3(0.2, 0.3, 0.5) + d.y;
    };
    ibl::CubeMap cube = ibl::test::makeCube(32, clearSky);
    cube.faces[2].at(20, 12) = glm::vec4(2e4f, 1.9e4f, 1.6e4f, 1.0f); // a one-texel sun on +Y
    const ibl::SunInProbe withSun = ibl::measureSunInProbe(cube, ibl::Executor::cpu(), 4);
    ASSERT_TRUE(withSun.detected);
    ASSERT_EQ(withSun.keptError.size(), 11u);
    double kept = 0.0, extracted = 0.0;
    for (std::size_t k = 0; k < 11; ++k)
        kept += withSun.keptError[k], extracted += withSun.extractedError[k];
    std::printf("sun in the probe: mean column error %.1f%% kept, %.1f%% extracted\n", 100 * kept / 11,
                100 * extracted / 11);
    EXPECT_GT(kept, 2.0 * extracted);
    EXPECT_EQ(withSun.warning.rfind("sun detected and left in the probe: runtime error ", 0), 0u)
        << withSun.warning;
    EXPECT_NE(withSun.warning.find("extract it: iblbake --extract-sun, scene key environment.extractSun"),
              std::string::npos);
    const ibl::SunInProbe noSun =
        ibl::measureSunInProbe(ibl::test::makeCube(32, sky), ibl::Executor::cpu(), 4);
    EXPECT_FALSE(noSun.detected);
    EXPECT_TRUE(noSun.warning.empty());
}

// A compact area light (a 3 x 3-texel softbox of 8.8e-3 sr on a 64 px cube: over the sun detector's
// 3e-3 sr, under kCompactLightMaxSolidAngle): no sun, but the check measures it and names the limit that
// extracts it; given that limit, it is the sun (the detection the bake would run).
TEST(SunInProbe, WarnsOfACompactLightAndNamesTheLimitThatExtractsIt) {
    auto sky = [](const glm::dvec3& d) {
        return d.y < 0.0 ? glm::dvec3(0.1) : glm::dvec3(0.2, 0.3, 0.5) + d.y;
    };
    ibl::CubeMap cube = ibl::test::makeCube(ibl::kSunInProbeFaceSize, sky);
    for (int y = 40; y < 43; ++y)
        for (int x = 20; x < 23; ++x)
            cube.faces[2].at(x, y) = glm::vec4(400.0f, 380.0f, 300.0f, 1.0f); // on +Y
    const ibl::SunInProbe compact = ibl::measureSunInProbe(cube, ibl::Executor::cpu(), 4);
    ASSERT_TRUE(compact.detected);
    EXPECT_TRUE(compact.compactLight);
    double kept = 0.0, extracted = 0.0;
    for (std::size_t k = 0; k < compact.keptError.size(); ++k)
        kept += compact.keptError[k], extracted += compact.extractedError[k];
    std::printf("compact light (disk of %.1f degrees) in the probe: mean column error %.1f%% kept, %.1f%% "
                "extracted\n",
                compact.angularRadiusDegrees, 100 * kept / 11, 100 * extracted / 11);
    EXPECT_GT(kept, 2.0 * extracted);
    EXPECT_EQ(compact.warning.rfind("compact light (disk of ", 0), 0u) << compact.warning;
    EXPECT_NE(compact.warning.find("extract it: iblbake --extract-sun --sun-max-solid-angle 0.02, scene keys "
                                   "environment.extractSun and environment.sunMaxSolidAngle"),
              std::string::npos)
        << compact.warning;

    ibl::SunDetectSettings limit;
    limit.maxSolidAngle = ibl::kCompactLightMaxSolidAngle;
    const ibl::SunInProbe asSun = ibl::measureSunInProbe(cube, ibl::Executor::cpu(), 4, limit);
    ASSERT_TRUE(asSun.detected);
    EXPECT_FALSE(asSun.compactLight);
    EXPECT_EQ(asSun.warning.rfind("sun detected and left in the probe: ", 0), 0u) << asSun.warning;
    EXPECT_EQ(asSun.keptError, compact.keptError);
}
