// Hostile inputs of a build farm (issue 17): image headers that claim huge sizes, devices, FIFOs and
// symlink loops named as inputs, oversized scene files and manifests, values out of range, outputs that
// would leave the scene's directory. Each must get a one-line error naming the file or key and the cause,
// exit 1, and leave the directory exactly as it was. The headers claim sizes; the files stay small.
#include "cli_runner.h"
#include "scene_test_support.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <map>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

using namespace ibl::test;
using nlohmann::json;

// Every path under `dir` with its size (directories, links and others as -1), symbolic links not followed
// (a loop must not stop the listing): what a failed command must leave unchanged.
void addListing(const fs::path& root, const fs::path& dir, std::map<std::string, std::intmax_t>& out) {
    for (const auto& e : fs::directory_iterator(dir)) {
        const fs::file_status status = fs::symlink_status(e.path());
        out[e.path().lexically_relative(root).string()] =
            fs::is_regular_file(status) ? std::intmax_t(fs::file_size(e.path())) : -1;
        if (fs::is_directory(status)) addListing(root, e.path(), out);
    }
}

std::map<std::string, std::intmax_t> listing(const fs::path& dir) {
    std::map<std::string, std::intmax_t> out;
    addListing(dir, dir, out);
    return out;
}

// OpenEXR `bytes` with the value of attribute `name` of `type` overwritten in place by `value`'s bytes
// (OpenEXR file layout: name\0 type\0, int32 size, then the value; integers little-endian, as this machine).
template <typename Value>
std::string withAttributeValue(std::string bytes, const char* name, const char* type, const Value& value) {
    const std::string key = std::string(name) + '\0' + type + '\0';
    const std::size_t at = bytes.find(key);
    EXPECT_NE(at, std::string::npos) << name;
    if (at != std::string::npos) std::memcpy(&bytes[at + key.size() + 4], &value, sizeof value);
    return bytes;
}

// The bytes of a small OpenEXR (64 x 32, float RGB) whose header is rewritten to claim width x height:
// its dataWindow and displayWindow (box2i) are patched in place. 64 KB of zeros after it give the offset
// table of the claimed rows something to read, so that the header is accepted.
std::string exrClaiming(const fs::path& dir, int width, int height) {
    const fs::path good = dir / "good_for_patch.exr";
    writeLatLong(good, 0.5f);
    std::string bytes = readBytes(good);
    fs::remove(good);
    const std::array<std::int32_t, 4> box = {0, 0, width - 1, height - 1};
    for (const char* name : {"dataWindow", "displayWindow"})
        bytes = withAttributeValue(bytes, name, "box2i", box);
    return bytes + std::string(64 << 10, '\0');
}

// A Radiance HDR header claiming width x height, followed by a few bytes of (bad) pixel data.
std::string hdrClaiming(int width, int height) {
    return "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(height) + " +X " +
           std::to_string(width) + "\n" + std::string(64, '\x02');
}

class HostileInputs : public ::testing::Test {
  protected:
    void SetUp() override {
        dir = freshTempDir(::testing::UnitTest::GetInstance()->current_test_info()->name());
        writeLatLong(dir / "sky.exr", 0.5f);
    }
    void TearDown() override { fs::remove_all(dir); }

    // Runs `args` (in `dir`) and requires a clean refusal: exit 1, one line "iblbake: error: ..." holding
    // every one of `expected` (the file or key named, the cause), and `dir` exactly as before.
    void expectRefused(const std::string& args, const std::vector<std::string>& expected,
                       const std::string& environment = "") {
        const auto before = listing(dir);
        expectOneLineRefusal(args, expected, environment);
        EXPECT_EQ(listing(dir), before) << args << " left something behind";
    }
    void expectOneLineRefusal(const std::string& args, const std::vector<std::string>& expected,
                              const std::string& environment = "") {
        const CliRun r = runProgram("cd " + dir.string() + " && " + environment + IBLBAKE_CLI, args);
        EXPECT_TRUE(r.exitCode == 1 || r.exitCode == 2) << args << ": " << r.err; // 2: a usage error
        EXPECT_EQ(lineCount(r.err), 1) << args << ": " << r.err;
        EXPECT_EQ(r.err.rfind("iblbake: error: ", 0), 0u) << args << ": " << r.err;
        EXPECT_LT(r.err.size(), 400u) << args; // long values are shortened
        for (const std::string& text : expected)
            EXPECT_NE(r.err.find(text), std::string::npos) << args << ": '" << text << "' not in " << r.err;
    }

    // A scene with `environment` and `outputs` merged over a small valid one.
    fs::path scene(const std::string& name, const json& patch) {
        json s = {{"environment", {{"file", "sky.exr"}}},
                  {"outputs", {{"directory", "out"}, {"faceSize", 8}, {"quality", "draft"}}}};
        s.merge_patch(patch);
        writeText(dir / name, s.dump());
        return dir / name;
    }

    fs::path dir;
};

const std::string kSpecular = "specular --size 8 --quality draft --backend cpu -o s.ktx2 ";

TEST_F(HostileInputs, ImageHeadersClaimingHugeSizesAreRefusedBeforeReadingPixels) {
    // 262661 x 15105: 3.97e9 pixels, over the 2^28 limit, refused from the header.
    writeText(dir / "huge.exr", exrClaiming(dir, 262661, 15105));
    expectRefused(
        kSpecular + "huge.exr --layout latlong",
        {"huge.exr", "262661x15105", "more than the limit of 268435456", "IBLBAKE_MAX_IMAGE_PIXELS"});
    writeText(dir / "huge.hdr", hdrClaiming(262661, 15105));
    expectRefused(kSpecular + "huge.hdr", {"huge.hdr", "more than the limit"});
    // 525341 x 59 fits no layout: refused from the header, not after reading 31 million pixels.
    writeText(dir / "wide.hdr", hdrClaiming(525341, 59));
    expectRefused(kSpecular + "wide.hdr", {"wide.hdr", "cannot tell the layout of a 525341x59 image"});
    expectRefused(kSpecular + "wide.hdr --layout latlong", {"wide.hdr", "2:1", "525341x59"});
    writeText(dir / "wide.exr", exrClaiming(dir, 525341, 59));
    expectRefused("inspect wide.exr", {"wide.exr", "525341x59"});
    // 100663297 x 1 (under the pixel limit): no layout either.
    writeText(dir / "line.exr", exrClaiming(dir, 100663297, 1));
    expectRefused(kSpecular + "line.exr", {"line.exr"});
    // A 16384 x 8192 lat-long within the limit whose pixels are missing: read strip by strip, it fails at
    // the first missing one instead of after taking memory for the whole claim.
    writeText(dir / "truncated.hdr", hdrClaiming(16384, 8192));
    expectRefused(kSpecular + "truncated.hdr", {"truncated.hdr", "cannot read pixels"});
    writeText(dir / "truncated.exr", exrClaiming(dir, 16384, 8192));
    expectRefused(kSpecular + "truncated.exr", {"truncated.exr", "cannot read pixels"});
    expectRefused("calibrate truncated.exr --scale 2 -o c.exr", {"truncated.exr", "cannot read pixels"});
}

// Found by fuzz/image_header.cpp: OpenEXR 3.1 takes the memory a header attribute claims before reading
// it (a 1.3 KB file claimed a 1.8 GB string). The header is walked first (baker/src/ingest/exr_header.cpp).
TEST_F(HostileInputs, OpenExrHeaderClaimsAreRefusedBeforeOpenExrTakesMemory) {
    const std::string good = readBytes(dir / "sky.exr");
    // `good` with one attribute (name\0type\0, int32 size, value) put first in its header.
    const auto withAttribute = [&](std::string_view nameAndType, std::int32_t size,
                                   const std::string& value) {
        char sizeBytes[4];
        std::memcpy(sizeBytes, &size, 4); // OpenEXR is little-endian, as this machine
        return good.substr(0, 8) + std::string(nameAndType) + std::string(sizeBytes, 4) + value +
               good.substr(8);
    };
    using namespace std::string_view_literals;
    writeText(dir / "string.exr", withAttribute("Software\0string\0"sv, 1836085861, "x"));
    expectRefused(kSpecular + "string.exr",
                  {"string.exr", "damaged OpenEXR header", "Software claims 1836085861 bytes"});
    const std::int32_t previewSize[2] = {65535, 65535};
    writeText(dir / "preview.exr",
              withAttribute("thumb\0preview\0"sv, 12,
                            std::string(reinterpret_cast<const char*>(previewSize), 8) + "rgba"));
    expectRefused(kSpecular + "preview.exr", {"preview.exr", "the preview claims 65535x65535 pixels"});
    // A fixed-size type given another size would make OpenEXR read on from elsewhere than the walk did.
    writeText(dir / "box.exr", withAttribute("window2\0box2i\0"sv, 20, std::string(20, '\0')));
    expectRefused(kSpecular + "box.exr", {"box.exr", "window2 of type box2i has 20 bytes"});
    // 1 x 2^28 is within the pixel limit, but its chunk-offset table (8 bytes a chunk, allocated when
    // OpenEXR opens the file) is not in the file.
    writeText(dir / "tall.exr", exrClaiming(dir, 1, 1 << 28));
    expectRefused(kSpecular + "tall.exr", {"tall.exr", "1x268435456 data window needs",
                                           "chunk offsets, more than the rest of the file holds"});
}

// Found by fuzz/image_header.cpp: a small tiled OpenEXR whose tiledesc claims huge tiles; OpenEXR 3.1
// allocates a tile's decoding buffer when it opens the file. The claim is held to the pixel limit.
TEST_F(HostileInputs, OpenExrTilesLargerThanThePixelLimitAreRefused) {
    OIIO::ImageSpec spec(32, 16, 3, OIIO::TypeDesc::HALF);
    spec.tile_width = spec.tile_height = 16;
    const std::vector<float> pixels(std::size_t(32) * 16 * 3, 0.5f);
    {
        const std::string file = (dir / "tiled.exr").string();
        auto out = OIIO::ImageOutput::create(file);
        ASSERT_TRUE(out && out->open(file, spec)) << OIIO::geterror();
        ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
        ASSERT_TRUE(out->close());
    }
    const CliRun ok = runProgram("cd " + dir.string() + " && " + IBLBAKE_CLI, "inspect tiled.exr");
    EXPECT_EQ(ok.exitCode, 0) << ok.err;

    const std::string tiled = readBytes(dir / "tiled.exr");
    const auto claimingTiles = [&](std::uint32_t width, std::uint32_t height) {
        return withAttributeValue(tiled, "tiles", "tiledesc", std::array<std::uint32_t, 2>{width, height});
    };
    writeText(dir / "huge_tiles.exr", claimingTiles(1u << 30, 1u << 30));
    expectRefused("inspect huge_tiles.exr", {"huge_tiles.exr", "damaged OpenEXR header",
                                             "1073741824x1073741824 tiles are larger than the limit of "
                                             "268435456 pixels (IBLBAKE_MAX_IMAGE_PIXELS)"});
    // Tiles within the pixel limit pass the walk: a 64x64 tile of a 32x16 image is legal OpenEXR.
    writeText(dir / "big_tiles.exr", claimingTiles(64, 64));
    const CliRun big = runProgram("cd " + dir.string() + " && " + IBLBAKE_CLI, "inspect big_tiles.exr");
    EXPECT_EQ(big.err.find("damaged OpenEXR header"), std::string::npos) << big.err;
}

TEST_F(HostileInputs, ThePixelLimitIsSetByItsVariable) {
    expectRefused(kSpecular + "sky.exr", {"sky.exr", "64x32 is 2048 pixels, more than the limit of 2047"},
                  "IBLBAKE_MAX_IMAGE_PIXELS=2047 ");
    expectRefused(kSpecular + "sky.exr", {"IBLBAKE_MAX_IMAGE_PIXELS", "'lots'", "not a whole number"},
                  "IBLBAKE_MAX_IMAGE_PIXELS=lots ");
    const CliRun ok = runProgram("cd " + dir.string() + " && IBLBAKE_MAX_IMAGE_PIXELS=2048 " + IBLBAKE_CLI,
                                 kSpecular + "sky.exr");
    EXPECT_EQ(ok.exitCode, 0) << ok.err;
}

TEST_F(HostileInputs, DevicesFifosAndSymlinkLoopsAreRefusedBeforeAnythingReadsThem) {
    ASSERT_EQ(::mkfifo((dir / "fifo.hdr").c_str(), 0600), 0);
    fs::create_symlink("loop_b.hdr", dir / "loop_a.hdr");
    fs::create_symlink("loop_a.hdr", dir / "loop_b.hdr");
    fs::create_directory(dir / "folder.hdr");
    expectRefused(kSpecular + "/dev/zero", {"/dev/zero: is a character device, not a regular file"});
    expectRefused("inspect /dev/zero", {"/dev/zero: is a character device, not a regular file"});
    expectRefused(kSpecular + "fifo.hdr", {"fifo.hdr: is a FIFO, not a regular file"});
    expectRefused(kSpecular + "loop_a.hdr", {"loop_a.hdr: Too many levels of symbolic links"});
    expectRefused(kSpecular + "folder.hdr", {"folder.hdr: is a directory"});
    expectRefused(kSpecular + "missing.hdr", {"missing.hdr: no such file"});
    // In a scene: before the content hash; the scene file and the manifest themselves.
    scene("device.json", {{"environment", {{"file", "/dev/zero"}}}});
    expectRefused("bake device.json --cache cache --backend cpu --quiet",
                  {"device.json: environment.file: /dev/zero: is a character device"});
    scene("fifo.json", {{"environment", {{"file", "fifo.hdr"}}}});
    expectRefused("bake fifo.json --cache cache --backend cpu --quiet",
                  {"fifo.json: environment.file:", "fifo.hdr: is a FIFO"});
    scene("loop.json", {{"environment", {{"file", "loop_a.hdr"}}}});
    expectRefused("bake loop.json --cache cache --backend cpu --quiet",
                  {"loop.json: environment.file:", "Too many levels of symbolic links"});
    ASSERT_EQ(::mkfifo((dir / "scene_fifo.json").c_str(), 0600), 0);
    expectRefused("bake /dev/zero --cache cache", {"/dev/zero: is a character device"});
    expectRefused("bake scene_fifo.json --cache cache", {"scene_fifo.json: is a FIFO"});
    expectRefused("plan scene_fifo.json", {"scene_fifo.json: is a FIFO"});
    expectRefused("batch /dev/zero", {"/dev/zero: is a character device"});
    expectRefused("batch scene_fifo.json", {"scene_fifo.json: is a FIFO"});
}

TEST_F(HostileInputs, OversizedSceneFilesAndManifestsAreRefusedBeforeParsing) {
    // Sparse: the size is claimed, not written.
    for (const char* name : {"big_scene.json", "big_manifest.json"}) {
        writeText(dir / name, "{");
        fs::resize_file(dir / name, std::uintmax_t(17) << 20);
    }
    expectRefused("bake big_scene.json --cache cache",
                  {"big_scene.json: is 17825792 bytes, more than the 16777216 bytes a scene file may have"});
    expectRefused(
        "batch big_manifest.json",
        {"big_manifest.json: is 17825792 bytes, more than the 16777216 bytes a batch manifest may have"});
}

TEST_F(HostileInputs, SceneValuesOutOfRangeAreRefusedWithTheirRange) {
    const json probe = {{"name", "p"},
                        {"capture", "sky.exr"},
                        {"position", {0, 0, 0}},
                        {"proxy", {{"shape", "box"}, {"halfExtents", {1e308, 1, 1}}}}};
    scene("half.json", {{"probes", {probe}}});
    expectRefused("bake half.json --cache cache --backend cpu --quiet",
                  {"half.json: probes[0].proxy.halfExtents: must be a number from 0 to 1e+09, not 1e+308"});
    json faded = probe;
    faded["proxy"] = {{"shape", "sphere"}, {"radius", 1}};
    faded["fadeDistance"] = 1e300;
    scene("fade.json", {{"probes", {faded}}});
    expectRefused("bake fade.json --cache cache --backend cpu --quiet",
                  {"fade.json: probes[0].fadeDistance: must be a number from 0 to 1e+09, not 1e+300"});
    scene("rotation.json", {{"environment", {{"rotation", 1e308}}}});
    expectRefused("bake rotation.json --cache cache --backend cpu --quiet",
                  {"rotation.json: environment.rotation: must be a number from -360 to 360, not 1e+308"});
    scene("face.json", {{"outputs", {{"faceSize", 8192}}}});
    expectRefused("bake face.json --cache cache --quiet", {"face.json: outputs.faceSize:", "4096"});
}

TEST_F(HostileInputs, CommandLineValuesOutOfRangeAreRefused) {
    expectRefused(kSpecular + "sky.exr --levels 1e9", {"--levels"});
    expectRefused(kSpecular + "sky.exr --levels -1", {"--levels", "1 to 13"});
    expectRefused(kSpecular + "sky.exr --levels 0", {"--levels", "1 to 13"});
    expectRefused(kSpecular + "sky.exr --levels 5", {"--levels: the level count 5 is not from 1 to 4"});
    expectRefused(kSpecular + "sky.exr --samples 4294967295", {"--samples"});
    expectRefused("specular sky.exr --size 8192 -o s.ktx2",
                  {"--size: 8192 is not a power of two from 1 to 4096"});
    expectRefused("calibrate sky.exr --scale 1e308 -o c.exr",
                  {"--scale", "sky.exr", "calibration factor 1e+308", "beyond the largest float"});
    expectRefused(kSpecular + "sky.exr --rotate 1e30", {"--rotate", "from -360 to 360"});
}

TEST_F(HostileInputs, LongAndBinaryTextIsShortenedAndQuoted) {
    json s = json::parse(readBytes(scene("long.json", json::object())));
    s[std::string(10 << 20, 'k')] = 1; // a 10 MB unknown key
    writeText(dir / "long.json", s.dump());
    expectRefused("bake long.json --cache cache --quiet", {"long.json: 'kkkk", "...': unknown key"});
    scene("nul.json", {{"environment", {{"file", std::string("a\0b.hdr", 7)}}}});
    expectRefused("bake nul.json --cache cache --quiet",
                  {"nul.json: environment.file:", "'a\\x00b.hdr' holds control bytes"});
}

TEST_F(HostileInputs, RelativeOutputsMayNotLeaveTheScenesDirectory) {
    fs::create_directories(dir / "scenes" / "deep");
    writeLatLong(dir / "scenes" / "deep" / "sky.exr", 0.5f);
    writeText(
        dir / "scenes" / "deep" / "escape.json",
        json({{"environment", {{"file", "sky.exr"}}}, {"outputs", {{"directory", "../../etc"}}}}).dump());
    expectRefused("bake scenes/deep/escape.json --cache cache --quiet",
                  {"escape.json: outputs.directory: '../../etc' leaves the scene's directory"});
    writeText(
        dir / "scenes" / "deep" / "sneaky.json",
        json({{"environment", {{"file", "sky.exr"}}}, {"outputs", {{"directory", "a/../../x"}}}}).dump());
    expectRefused("bake scenes/deep/sneaky.json --cache cache --quiet",
                  {"outputs.directory: 'a/../../x' leaves"});
    writeText(dir / "scenes" / "deep" / "items.json", R"([{"hdri": "sky.exr", "output": "../../etc-x"}])");
    expectRefused("batch scenes/deep/items.json --quiet",
                  {"items.json: items[0].output: '../../etc-x' leaves the manifest's directory"});
    writeText(dir / "scenes" / "deep" / "ids.json", R"([{"hdri": "sky.exr", "id": "../../x"}])");
    expectRefused("batch scenes/deep/ids.json --quiet", {"ids.json: items[0].id: '../../x' must be"});
}

TEST_F(HostileInputs, EveryOutputIsCheckedBeforeAnyWork) {
    fs::create_directory(dir / "folder");
    writeText(dir / "plain_file", "x");
    expectRefused(kSpecular + "sky.exr --preview folder", {"folder: is a directory"});
    expectRefused(kSpecular + "sky.exr --exr plain_file", {"plain_file: is not a directory"});
    expectRefused("specular sky.exr --size 8 -o folder", {"folder: is a directory"});
    expectRefused("specular sky.exr --size 8 -o missing/s.ktx2",
                  {"missing/s.ktx2: directory missing does not exist"});
}

// A small tmpfs at dir/name (mounting needs root: skipped otherwise), filled to the last byte when `full`,
// or remounted read-only; unmounted by the fixture.
class FullAndReadOnlyDisks : public HostileInputs {
  protected:
    bool mountSmall(const std::string& name, bool full, bool readOnly) {
        const fs::path at = dir / name;
        fs::create_directory(at);
        if (std::system(("mount -t tmpfs -o size=256k tmpfs " + at.string() + " 2>/dev/null").c_str()) != 0)
            return false;
        mounts.push_back(at);
        if (full) // dd stops at the end of the device
            std::system(("dd if=/dev/zero of=" + (at / "filler").string() + " bs=4k 2>/dev/null").c_str());
        if (readOnly) std::system(("mount -o remount,ro " + at.string()).c_str());
        return true;
    }
    void TearDown() override {
        for (const fs::path& at : mounts)
            std::system(("umount " + at.string()).c_str());
        HostileInputs::TearDown();
    }
    std::vector<fs::path> mounts;
};

TEST_F(FullAndReadOnlyDisks, WriteFailuresNameTheOutputAndTheSystemsReason) {
    if (!mountSmall("full", true, false) || !mountSmall("ro", false, true))
        GTEST_SKIP() << "mounting a tmpfs needs root";
    const std::string noSpace = "No space left on device", readOnly = "Read-only file system";
    expectRefused("diffuse sky.exr --backend cpu -o full/d.json", {"full/d.json: cannot write", noSpace});
    expectRefused("calibrate sky.exr --scale 2 -o full/c.exr", {"full/c.exr: cannot write", noSpace});
    expectRefused("dfg --size 8 --samples 16 --backend cpu -o full/dfg.exr", {"full/dfg.exr", noSpace});
    expectRefused("specular --size 8 --quality draft --backend cpu -o ro/s.ktx2 sky.exr",
                  {"ro/s.ktx2", readOnly});
    // Every output of a command or none: the first output fits, a later one does not.
    expectRefused(kSpecular + "sky.exr --preview full/p.png", {"full/p.png: cannot write", noSpace});
    expectRefused(kSpecular + "sky.exr --exr full/levels", {"full/levels", noSpace});
    expectRefused("diffuse sky.exr --backend cpu -o d.json --irradiance-cube full/i.ktx2 --irradiance-size 8",
                  {"full/i.ktx2", noSpace});
    // A scene whose outputs cannot be written: the output and the reason, not the environment, are named,
    // and the tree and the cache (with an earlier bake's entries in it) are as they were, every stage's
    // work included (issue 17, item 4).
    scene("good.json", {{"outputs", {{"directory", "good"}}}});
    ASSERT_EQ(runProgram("cd " + dir.string() + " && " + IBLBAKE_CLI, "bake good.json --cache cache --quiet")
                  .exitCode,
              0);
    scene("to_full.json", {{"outputs", {{"directory", "full/out"}, {"dfgSize", 16}}}});
    expectRefused("bake to_full.json --cache cache --backend cpu --quiet",
                  {"to_full.json: full/out/", noSpace});
    scene("to_ro.json", {{"outputs", {{"directory", "ro/out"}, {"dfgSize", 16}}}});
    expectRefused("bake to_ro.json --cache cache --backend cpu --quiet", {"to_ro.json", "ro/out", readOnly});
    expectRefused("bake to_ro.json --force --cache ro/cache --backend cpu --quiet", {"ro/cache", readOnly});
}

// A bake that fails anywhere leaves the output tree and the cache exactly as they were: no output
// directory, no cache entry of the stages that ran before the failure (here the DFG LUT, planned first),
// no staging directory (issue 17, item 4).
TEST_F(HostileInputs, AFailedBakeLeavesTheTreeAndTheCacheAsTheyWere) {
    scene("good.json", {{"outputs", {{"directory", "good"}}}});
    ASSERT_EQ(runProgram("cd " + dir.string() + " && " + IBLBAKE_CLI, "bake good.json --cache cache --quiet")
                  .exitCode,
              0);
    // A product path that is a directory: refused before any work.
    fs::create_directories(dir / "taken" / "specular.ktx2");
    scene("taken.json", {{"outputs", {{"directory", "taken"}, {"dfgSize", 16}}}});
    expectRefused("bake taken.json --cache cache --backend cpu --quiet",
                  {"taken.json", "taken/specular.ktx2: is a directory"});
    // An environment that hashes but does not decode: the DFG stage has run when the environment fails.
    writeText(dir / "broken.exr", std::string("\x76\x2f\x31\x01", 4) + std::string(4096, '\x07'));
    scene("broken.json", {{"environment", {{"file", "broken.exr"}}},
                          {"outputs", {{"directory", "new/deep"}, {"dfgSize", 16}}}});
    expectRefused("bake broken.json --cache cache --backend cpu --quiet", {"broken.exr"});
    expectRefused("bake broken.json --backend cpu --quiet", {"broken.exr"}); // the cache inside new/deep
}

// Staging directories left by runs that died (SIGKILL, a lost node) are removed by the next run; those of
// live runs (their owner file locked) and fresh ones without an owner file are left alone.
TEST_F(HostileInputs, StaleStagingIsRemovedOnlyWhenItsOwnerIsGone) {
    const fs::path cache = dir / "cache";
    auto staging = [&](const std::string& name, bool owner) {
        fs::create_directories(cache / name);
        writeText(cache / name / "partial.ktx2", "x");
        if (owner) writeText(cache / name / ".owner", "");
        return cache / name;
    };
    staging(".staging-dead-1", true);
    const fs::path live = staging(".staging-live-1", true);
    const int lock = ::open((live / ".owner").c_str(), O_RDONLY);
    ASSERT_EQ(::flock(lock, LOCK_EX | LOCK_NB), 0); // held by this process: a live run
    const fs::path old = staging(".staging-ownerless-old", false);
    fs::last_write_time(old, fs::file_time_type::clock::now() - std::chrono::hours(2));
    staging(".staging-ownerless-new", false);
    staging(".trash-1", false);
    scene("s.json", json::object());
    const CliRun r =
        runProgram("cd " + dir.string() + " && " + IBLBAKE_CLI, "bake s.json --cache cache --quiet");
    ::close(lock);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::vector<std::string> left;
    for (const auto& e : fs::directory_iterator(cache))
        if (e.path().filename().string()[0] == '.') left.push_back(e.path().filename().string());
    std::sort(left.begin(), left.end());
    EXPECT_EQ(left, (std::vector<std::string>{".staging-live-1", ".staging-ownerless-new"}));
}

} // namespace
