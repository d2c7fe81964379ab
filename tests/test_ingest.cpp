// Ingest front end: reading, layout detection, colour, repair and area-correct resampling.
#include "cli_runner.h"
#include "iblbake/baker/ingest.h"
#include "iblbake/core/error.h"
#include "iblbake/core/numeric.h"
#include "ingest_internal.h"
#include "test_support.h"

#include <cube.h>

#include <OpenEXR/ImfEnvmap.h>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace {

namespace fs = std::filesystem;
using ibl::CubeMap;
using ibl::EnvLayout;
using ibl::ImageRGBA;
using ibl::IngestSettings;
using ibl::LatLongPixels;

constexpr double kPi = std::numbers::pi;

// ---------------------------------------------------------------------------------------------------
// Helpers

class TempDir {
  public:
    TempDir() {
        static std::atomic<int> counter{0};
        path_ = fs::temp_directory_path() /
                ("iblbake_test_ingest_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
        fs::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path_, ec);
    }
    fs::path operator/(const std::string& name) const { return path_ / name; }

  private:
    fs::path path_;
};

struct WriteOptions {
    OIIO::TypeDesc format = OIIO::TypeDesc::FLOAT;
    int channels = 3;
    std::vector<std::pair<std::string, std::string>> attributes;
    std::vector<float> chromaticities; // 8 values, EXR only
};

// Writes RGB(A) of `image` with OIIO (the same library the ingest reads with, but a different code path).
void writeImage(const fs::path& path, const ImageRGBA& image, const WriteOptions& options = {}) {
    OIIO::ImageSpec spec(image.width, image.height, options.channels, options.format);
    for (const auto& [k, v] : options.attributes)
        spec.attribute(k, v);
    if (options.chromaticities.size() == 8)
        spec.attribute("chromaticities", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8),
                       options.chromaticities.data());
    auto out = OIIO::ImageOutput::create(path.string());
    ASSERT_TRUE(out) << OIIO::geterror();
    ASSERT_TRUE(out->open(path.string(), spec)) << out->geterror();
    std::vector<float> data;
    for (const glm::vec4& p : image.pixels)
        for (int c = 0; c < options.channels; ++c)
            data.push_back(p[c]);
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, data.data())) << out->geterror();
    ASSERT_TRUE(out->close());
}

// A lat-long pixel's centre direction and exact solid angle in a placement's grid (latlong_pixels.h); pixel
// centres unless said otherwise, as ingest reads a file without OpenEXR's envmap attribute.
glm::dvec3 latLongPixelDirection(int x, int y, int w, int h, LatLongPixels p = LatLongPixels::Centre) {
    ibl::vec3 d = ibl::directionFromLatlong(float(ibl::latLongPixelCentre(p, x, w)),
                                            float(ibl::latLongPixelCentre(p, y, h)));
    return glm::dvec3(d);
}

double latLongPixelSolidAngle(int x, int y, int w, int h, LatLongPixels p = LatLongPixels::Centre) {
    const double du = ibl::latLongPixelEdge(p, x + 1, w) - ibl::latLongPixelEdge(p, x, w);
    const double zTop = std::cos(kPi * ibl::latLongPixelEdge(p, y, h)),
                 zBottom = std::cos(kPi * ibl::latLongPixelEdge(p, y + 1, h));
    return 2.0 * kPi * du * (zTop - zBottom);
}

ImageRGBA latLongOf(int w, int h, const std::function<glm::vec3(int, int)>& value) {
    ImageRGBA im(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            im.at(x, y) = glm::vec4(value(x, y), 1.0f);
    return im;
}

bool sameBits(const CubeMap& a, const CubeMap& b) {
    if (a.faceSize != b.faceSize) return false;
    for (int f = 0; f < 6; ++f)
        if (std::memcmp(a.faces[f].pixels.data(), b.faces[f].pixels.data(),
                        a.faces[f].pixels.size() * sizeof(glm::vec4)) != 0)
            return false;
    return true;
}

glm::dvec3 latLongEnergy(const ImageRGBA& im, LatLongPixels p) {
    glm::dvec3 e(0.0);
    for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x)
            e += glm::dvec3(glm::vec3(im.at(x, y))) * latLongPixelSolidAngle(x, y, im.width, im.height, p);
    return e;
}

glm::dvec3 cubeEnergy(const CubeMap& cube) {
    glm::dvec3 e(0.0);
    for (const ImageRGBA& face : cube.faces)
        for (int j = 0; j < cube.faceSize; ++j)
            for (int i = 0; i < cube.faceSize; ++i)
                e += glm::dvec3(glm::vec3(face.at(i, j))) *
                     double(ibl::cubeTexelSolidAngle(i, j, cube.faceSize));
    return e;
}

glm::dvec3 texelDirection(int face, int i, int j, int n) {
    return glm::normalize(glm::dvec3(ibl::cubeFaceDirection(face, (i + 0.5f) / n, (j + 0.5f) / n)));
}

double luminance(const glm::vec4& p) {
    return 0.2126 * p.x + 0.7152 * p.y + 0.0722 * p.z;
}

// Solid-angle-weighted relative RMS difference of two cubes of the same size.
double relativeRms(const CubeMap& a, const CubeMap& b) {
    double num = 0.0, den = 0.0;
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < a.faceSize; ++j)
            for (int i = 0; i < a.faceSize; ++i) {
                const double w = ibl::cubeTexelSolidAngle(i, j, a.faceSize);
                const glm::dvec3 pa(glm::vec3(a.faces[f].at(i, j))), pb(glm::vec3(b.faces[f].at(i, j)));
                num += w * glm::dot(pa - pb, pa - pb);
                den += w * glm::dot(pb, pb);
            }
    return std::sqrt(num / den);
}

struct Texel {
    int face = 0, i = 0, j = 0;
};

Texel brightest(const CubeMap& cube) {
    Texel best;
    double bestLum = -1.0;
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < cube.faceSize; ++j)
            for (int i = 0; i < cube.faceSize; ++i)
                if (double l = luminance(cube.faces[f].at(i, j)); l > bestLum) {
                    bestLum = l;
                    best = {f, i, j};
                }
    return best;
}

double angleBetween(const glm::dvec3& a, const glm::dvec3& b) {
    return std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0));
}

// A smooth, direction-dependent RGB value that tells every direction apart.
glm::vec3 directionColor(const glm::dvec3& d) {
    return glm::vec3(0.5 * (glm::normalize(d) + 1.0));
}

// The largest distance of a cube's texel from directionColor of the texel's centre direction.
double worstDirectionColorError(const CubeMap& cube) {
    const int n = cube.faceSize;
    double worst = 0.0;
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                worst = std::max(worst, double(glm::length(glm::vec3(cube.faces[f].at(i, j)) -
                                                           directionColor(texelDirection(f, i, j, n)))));
    return worst;
}

ibl::SourceEnvironment ingest(const fs::path& file, IngestSettings settings = {}) {
    return ibl::ingestEnvironment({file}, settings);
}

std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const ibl::Error& e) {
        return e.what();
    }
    return "<no ibl::Error thrown>";
}

// ---------------------------------------------------------------------------------------------------
// Layout names

TEST(IngestLayout, NamesRoundTrip) {
    for (EnvLayout l : {EnvLayout::Auto, EnvLayout::LatLong, EnvLayout::ExrCube, EnvLayout::HorizontalCross,
                        EnvLayout::VerticalCross, EnvLayout::HorizontalStrip, EnvLayout::VerticalStrip,
                        EnvLayout::SixFiles})
        EXPECT_EQ(ibl::parseLayout(ibl::layoutName(l)), l) << ibl::layoutName(l);
    EXPECT_EQ(ibl::parseLayout("Equirect"), EnvLayout::LatLong);
    EXPECT_THROW(ibl::parseLayout("sphere"), ibl::Error);
}

// ---------------------------------------------------------------------------------------------------
// Lat-long -> cube resampling

TEST(IngestResample, ConstantEnvironmentGivesConstantCube) {
    const glm::vec3 c(0.25f, 1.0f, 3.5f);
    const ImageRGBA ll = latLongOf(96, 48, [&](int, int) { return c; });
    for (LatLongPixels placement : {LatLongPixels::Centre, LatLongPixels::OpenExr})
        for (int n : {1, 7, 16, 40}) {
            const CubeMap cube = ibl::resampleLatLongToCube(ll, n, placement);
            double worst = 0.0;
            for (const ImageRGBA& face : cube.faces)
                for (const glm::vec4& p : face.pixels)
                    worst = std::max(worst, double(glm::length(glm::vec3(p) - c) / glm::length(c)));
            EXPECT_LT(worst, 1e-5) << "face size " << n << ", " << ibl::latLongPixelsName(placement);
        }
}

TEST(IngestResample, DirectionEncodingLandsOnEachFace) {
    const int w = 512, h = 256, n = 32;
    const ImageRGBA ll =
        latLongOf(w, h, [&](int x, int y) { return directionColor(latLongPixelDirection(x, y, w, h)); });
    const CubeMap cube = ibl::resampleLatLongToCube(ll, n, LatLongPixels::Centre);
    for (int f = 0; f < 6; ++f) {
        double worst = 0.0;
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const glm::vec3 expected = directionColor(texelDirection(f, i, j, n));
                worst = std::max(worst, double(glm::length(glm::vec3(cube.faces[f].at(i, j)) - expected)));
            }
        // A texel's average differs from its centre value by ~(texel size)^2; a flip would be ~1.
        EXPECT_LT(worst, 0.01) << "face " << f;
    }
}

TEST(IngestResample, EnergyIsPreserved) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    const int w = 256, h = 128;
    ImageRGBA ll = latLongOf(w, h, [&](int, int) { return glm::vec3(uni(rng), uni(rng), uni(rng)); });
    for (int k = 0; k < 20; ++k) // a few bright spots, as in real skies
        ll.at(int(uni(rng) * (w - 1)), int(uni(rng) * (h - 1))) = glm::vec4(glm::vec3(500.0f * uni(rng)), 1);
    for (LatLongPixels placement : {LatLongPixels::Centre, LatLongPixels::OpenExr}) {
        const glm::dvec3 in = latLongEnergy(ll, placement);
        const std::string name = ibl::latLongPixelsName(placement);
        for (int n : {16, 45, 64, 128}) {
            const glm::dvec3 out = cubeEnergy(ibl::resampleLatLongToCube(ll, n, placement));
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(out[c] / in[c], 1.0, 1e-3)
                    << "face size " << n << " channel " << c << ", " << name;
            RecordProperty("energy_ratio_" + name + "_face_" + std::to_string(n),
                           std::to_string(out.y / in.y));
        }
    }
}

TEST(IngestResample, OnePixelSunKeepsItsEnergy) {
    const int w = 512, h = 256;
    struct Spot {
        int x, y;
        const char* where;
    };
    const Spot spots[] = {
        {128, 128, "+X equator"},          {0, 100, "seam column"},   {300, 0, "pole row"},
        {70, 3, "near the zenith"},        {200, 60, "+Y/+X region"}, {64, 90, "near a cube corner"},
        {383, 200, "-X below the horizon"}};
    double worstError = 0.0;
    for (int n : {128, 45}) {
        for (const Spot& s : spots) {
            ImageRGBA ll = latLongOf(w, h, [](int, int) { return glm::vec3(0.0f); });
            ll.at(s.x, s.y) = glm::vec4(1e5f, 1e5f, 1e5f, 1.0f);
            const double expected = 1e5 * latLongPixelSolidAngle(s.x, s.y, w, h);
            const CubeMap cube = ibl::resampleLatLongToCube(ll, n, LatLongPixels::Centre);
            const double got = cubeEnergy(cube).y;
            EXPECT_NEAR(got / expected, 1.0, 0.01) << s.where << ", face size " << n;
            worstError = std::max(worstError, std::fabs(got / expected - 1.0));
            // ... and it lands where the sun is: within a texel's width or two.
            const Texel t = brightest(cube);
            const double texelAngle = 2.0 / n;
            EXPECT_LT(
                angleBetween(texelDirection(t.face, t.i, t.j, n), latLongPixelDirection(s.x, s.y, w, h)),
                2.0 * texelAngle)
                << s.where << ", face size " << n;
        }
    }
    RecordProperty("worst_relative_energy_error", std::to_string(worstError));
}

// The resampling computes one texel's geometry for its mirror image, quarter turns and reflections (when the
// grid has them) and applies it to all: every texel must match the one computed on its own, within
// rounding. A wrong orbit (face, texel, column shift or reflection, mirrored rows) is off by the content's
// contrast, ~1.
TEST(IngestResample, SymmetricGeometryMatchesTexelByTexel) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    struct Case {
        int w, h, n;
        LatLongPixels placement;
        double rotate;
        bool alpha;
    };
    const Case cases[] = {
        {256, 128, 32, LatLongPixels::Centre, 0.0, false},  // mirror, quarter turns and reflections
        {128, 64, 24, LatLongPixels::Centre, 0.0, true},    // the same with alpha, a face size not 2^k
        {256, 128, 20, LatLongPixels::Centre, 0.7, true},   // rotated, with alpha
        {255, 128, 32, LatLongPixels::Centre, 0.0, false},  // width not a multiple of 4: mirror only
        {257, 129, 16, LatLongPixels::OpenExr, 0.0, false}, // OpenEXR placement: mirror only
        {256, 128, 15, LatLongPixels::Centre, 0.0, false},  // odd face: every texel on its own
    };
    double worstOfAll = 0.0;
    for (const Case& c : cases) {
        ImageRGBA ll = latLongOf(c.w, c.h, [&](int, int) { return glm::vec3(uni(rng), uni(rng), uni(rng)); });
        for (glm::vec4& p : ll.pixels)
            p.w = uni(rng);
        for (int k = 0; k < 20; ++k) // bright spots, placed with no symmetry
            ll.at(int(uni(rng) * float(c.w - 1)), int(uni(rng) * float(c.h - 1))) =
                glm::vec4(glm::vec3(1e4f * uni(rng)), 1.0f);
        const CubeMap fast =
            ibl::ingest::resampleLatLongToCubeRotated(ll, c.n, c.placement, c.rotate, c.alpha);
        const CubeMap reference =
            ibl::ingest::resampleLatLongToCubeRotated(ll, c.n, c.placement, c.rotate, c.alpha, false);
        double worst = 0.0;
        for (int f = 0; f < 6; ++f)
            for (std::size_t t = 0; t < fast.faces[f].pixels.size(); ++t)
                for (int ch = 0; ch < 4; ++ch) {
                    const double a = fast.faces[f].pixels[t][ch], b = reference.faces[f].pixels[t][ch];
                    worst = std::max(worst, std::fabs(a - b) / std::max({std::fabs(a), std::fabs(b), 1e-30}));
                }
        EXPECT_LE(worst, 1e-6) << c.w << "x" << c.h << " into " << c.n << ", "
                               << ibl::latLongPixelsName(c.placement) << ", rotation " << c.rotate;
        worstOfAll = std::max(worstOfAll, worst);
    }
    std::ostringstream worstText;
    worstText << worstOfAll;
    RecordProperty("worst_relative_difference", worstText.str());
}

// An image handed out block by block, as a streamed ingest does: counts what is held.
class CountedBlocks final : public ibl::ingest::LatLongBlocks {
  public:
    CountedBlocks(const ImageRGBA& image, int blockRows)
        : image_(image), blockRows_(blockRows), state_((image.height + blockRows - 1) / blockRows, 0) {}
    int width() const override { return image_.width; }
    int height() const override { return image_.height; }
    int blockRows() const override { return blockRows_; }
    const glm::vec4* acquire(int block) override {
        EXPECT_EQ(state_[std::size_t(block)], 0) << "block " << block << " asked for twice";
        state_[std::size_t(block)] = 1;
        maxHeld = std::max(maxHeld, ++held);
        return &image_.at(0, block * blockRows_);
    }
    void release(int block) override {
        EXPECT_EQ(state_[std::size_t(block)], 1) << "block " << block << " released but not held";
        state_[std::size_t(block)] = 2;
        --held;
    }
    int blockCount() const { return int(state_.size()); }
    int held = 0, maxHeld = 0;

  private:
    const ImageRGBA& image_;
    int blockRows_;
    std::vector<int> state_; // per block: 0 never held, 1 held, 2 released
};

// The streamed resampling (resampleLatLongBlocks) gives the whole image's cube bit for bit, in every case of
// the symmetry (see above), holding few of the blocks at once and asking for each block once.
TEST(IngestResample, BlocksGiveTheWholeImagesBits) {
    std::mt19937 rng(12);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    struct Case {
        int w, h, n, blockRows;
        LatLongPixels placement;
        double rotate;
        bool symmetry;
    };
    const Case cases[] = {
        {256, 128, 32, 8, LatLongPixels::Centre, 0.0, true},   // mirror, quarter turns and reflections
        {256, 128, 20, 5, LatLongPixels::Centre, 0.7, true},   // rotated: no reflections
        {257, 129, 16, 7, LatLongPixels::OpenExr, 0.0, true},  // mirror only, a last block shorter
        {256, 128, 15, 8, LatLongPixels::Centre, 0.0, true},   // odd face: every texel on its own
        {256, 128, 32, 8, LatLongPixels::Centre, 0.0, false},  // no symmetry
        {512, 256, 64, 16, LatLongPixels::Centre, -2.0, true}, // texels of about a row
    };
    for (const Case& c : cases) {
        ImageRGBA ll = latLongOf(c.w, c.h, [&](int, int) { return glm::vec3(uni(rng), uni(rng), uni(rng)); });
        for (int k = 0; k < 20; ++k) // bright spots
            ll.at(int(uni(rng) * float(c.w - 1)), int(uni(rng) * float(c.h - 1))) =
                glm::vec4(glm::vec3(1e4f * uni(rng)), 1.0f);
        const CubeMap whole =
            ibl::ingest::resampleLatLongToCubeRotated(ll, c.n, c.placement, c.rotate, false, c.symmetry);
        CountedBlocks blocks(ll, c.blockRows);
        const CubeMap streamed =
            ibl::ingest::resampleLatLongBlocks(blocks, c.n, c.placement, c.rotate, c.symmetry);
        EXPECT_TRUE(sameBits(whole, streamed)) << c.w << "x" << c.h << " into " << c.n << ", rotation "
                                               << c.rotate << ", symmetry " << c.symmetry;
        EXPECT_EQ(blocks.held, 0);
        // A texel reads a few rows: the blocks of its slab and those before, top and bottom, and the next
        // slab's, decoded meanwhile, however many blocks the image has.
        EXPECT_LE(blocks.maxHeld, 10) << "of " << blocks.blockCount() << " blocks, " << c.w << "x" << c.h;
    }
}

// A quarter turn maps the texel grid onto itself, so the rotated cube is the unrotated one permuted.
TEST(IngestResample, QuarterTurnMovesPlusZToPlusX) {
    TempDir dir;
    const int w = 128, h = 64, n = 16;
    const ImageRGBA ll =
        latLongOf(w, h, [&](int x, int y) { return directionColor(latLongPixelDirection(x, y, w, h)); });
    writeImage(dir / "ll.exr", ll);
    IngestSettings s;
    s.sourceFaceSize = n;
    const CubeMap plain = ingest(dir / "ll.exr", s).cube;
    s.rotateDegrees = 90.0f; // counter-clockwise seen from above: +Z -> +X
    const CubeMap turned = ingest(dir / "ll.exr", s).cube;
    double worst = 0.0;
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const glm::dvec3 d = texelDirection(f, i, j, n);
                const glm::dvec3 from(-d.z, d.y, d.x); // R(-90 deg) d: what was there before the turn
                const ibl::CubeCoord c = ibl::cubeCoordFromDirection(ibl::vec3(from));
                const glm::vec4 expected =
                    plain.faces[c.face].at(std::min(int(c.s * n), n - 1), std::min(int(c.t * n), n - 1));
                worst = std::max(worst, double(glm::length(glm::vec3(turned.faces[f].at(i, j) - expected))));
            }
    EXPECT_LT(worst, 1e-3);
    // The +X face now shows what +Z showed: +Z's centre colour is (0.5, 0.5, 1).
    EXPECT_NEAR(turned.faces[0].at(n / 2, n / 2).z, 1.0f, 0.05f);
}

// ---------------------------------------------------------------------------------------------------
// Files: repair, colour, errors

TEST(IngestFile, RepairsAndCountsBadPixels) {
    TempDir dir;
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    ImageRGBA ll = latLongOf(64, 32, [](int, int) { return glm::vec3(1.0f); });
    ll.at(5, 5) = glm::vec4(5.0f, 4.0f, 3.0f, 1.0f); // the largest finite value is 5
    ll.at(10, 10) = glm::vec4(nan, 1.0f, nan, 1.0f);
    ll.at(11, 10) = glm::vec4(inf, inf, inf, 1.0f);
    ll.at(12, 10) = glm::vec4(-inf, 1.0f, 1.0f, 1.0f);
    ll.at(13, 10) = glm::vec4(-0.5f, -2.0f, 1.0f, 1.0f);
    writeImage(dir / "bad.exr", ll);
    const auto env = ingest(dir / "bad.exr");
    EXPECT_EQ(env.report.nanRepaired, 2u);
    EXPECT_EQ(env.report.infRepaired, 4u); // three +Inf and one -Inf
    EXPECT_EQ(env.report.negativeRepaired, 2u);
    // +Inf became the largest finite value: the brightest pixel is now (5, 5, 5).
    EXPECT_NEAR(env.report.maxLuminanceIn, 5.0f, 1e-4f);
    for (const ImageRGBA& face : env.cube.faces)
        for (const glm::vec4& p : face.pixels)
            for (int c = 0; c < 3; ++c)
                ASSERT_TRUE(std::isfinite(p[c]) && p[c] >= 0.0f);
}

// An OpenEXR lat-long is resampled block by block as it is decoded (ingest.cpp ingestLatLongInBlocks): the
// cube, the repairs and the brightest luminance are those of the whole image read, repaired, converted and
// resampled, with and without a colour conversion, in scan-line and tiled files; a file with an infinity
// (whose repair takes the whole image's largest value) too.
TEST(IngestFile, OpenExrLatLongStreamsToTheWholeImagesCube) {
    TempDir dir;
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    std::mt19937 rng(13);
    std::uniform_real_distribution<float> uni(-0.1f, 4.0f);
    ImageRGBA ll = latLongOf(512, 256, [&](int, int) { return glm::vec3(uni(rng), uni(rng), uni(rng)); });
    ll.at(10, 10) = glm::vec4(nan, 1.0f, nan, 1.0f);
    ll.at(500, 250) = glm::vec4(-inf, 1.0f, 1.0f, 1.0f);
    ImageRGBA withInf = ll;
    withInf.at(40, 200) = glm::vec4(inf, 1.0f, 1.0f, 1.0f);
    writeImage(dir / "scanlines.exr", ll, {OIIO::TypeDesc::HALF});
    writeImage(dir / "float.exr", ll);
    writeImage(dir / "inf.exr", withInf);
    {
        OIIO::ImageSpec spec(ll.width, ll.height, 3, OIIO::TypeDesc::HALF);
        spec.tile_width = spec.tile_height = 32;
        auto out = OIIO::ImageOutput::create((dir / "tiled.exr").string());
        ASSERT_TRUE(out && out->open((dir / "tiled.exr").string(), spec));
        std::vector<float> data;
        for (const glm::vec4& p : ll.pixels)
            data.insert(data.end(), {p.x, p.y, p.z});
        ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, data.data()) && out->close());
    }
    for (const char* name : {"scanlines.exr", "float.exr", "inf.exr", "tiled.exr"})
        for (const char* working : {"lin_rec709", "acescg"}) {
            IngestSettings settings;
            settings.workingColorSpace = working;
            settings.sourceFaceSize = 48;
            const ibl::SourceEnvironment env = ingest(dir / name, settings);
            ibl::ingest::RawImage whole = ibl::ingest::readImage(dir / name);
            const ibl::ingest::RepairCounts repaired = ibl::ingest::sanitize(whole.pixels);
            const ibl::ingest::RepairCounts repairs =
                repaired + ibl::ingest::convertColorRepaired(whole.pixels, "lin_rec709", working, name);
            const CubeMap cube =
                ibl::ingest::resampleLatLongToCubeRotated(whole.pixels, 48, LatLongPixels::Centre, 0.0);
            EXPECT_TRUE(sameBits(env.cube, cube)) << name << " " << working;
            EXPECT_EQ(env.report.nanRepaired, repairs.nan) << name;
            EXPECT_EQ(env.report.infRepaired, repairs.inf) << name;
            EXPECT_EQ(env.report.negativeRepaired, repairs.negative) << name;
            EXPECT_GT(env.report.negativeRepaired, 1000u) << name;
            EXPECT_EQ(env.report.maxLuminanceIn,
                      ibl::ingest::maxLuminance(whole.pixels, ibl::ingest::luminanceWeights(working)))
                << name << " " << working;
        }
}

TEST(IngestFile, EightBitPngDecodesFromSrgb) {
    TempDir dir;
    const ImageRGBA ll = latLongOf(64, 32, [](int, int) { return glm::vec3(128.0f / 255.0f); });
    WriteOptions o;
    o.format = OIIO::TypeDesc::UINT8;
    writeImage(dir / "grey.png", ll, o);
    const auto env = ingest(dir / "grey.png");
    EXPECT_EQ(env.report.inputColorSpace, "srgb");
    // IEC 61966-2-1: ((128/255 + 0.055) / 1.055)^2.4 = 0.2158605
    EXPECT_NEAR(env.cube.faces[2].at(3, 3).y, 0.2158605f, 1e-5f);
    // ... unless the user says otherwise.
    IngestSettings s;
    s.inputColorSpace = "raw";
    EXPECT_NEAR(ingest(dir / "grey.png", s).cube.faces[2].at(3, 3).y, 128.0f / 255.0f, 1e-5f);
}

TEST(IngestFile, ReadsCommonFormats) {
    TempDir dir;
    const ImageRGBA ll =
        latLongOf(64, 32, [](int x, int y) { return glm::vec3(0.5f + x / 64.0f, 2.0f, 0.25f + y / 32.0f); });
    const CubeMap reference = ibl::resampleLatLongToCube(ll, 16, LatLongPixels::Centre);
    struct Format {
        const char* name;
        WriteOptions options;
        double tolerance;
    };
    WriteOptions half, dwab, tiff, hdr;
    half.format = OIIO::TypeDesc::HALF;
    dwab.format = OIIO::TypeDesc::HALF;
    dwab.attributes = {{"compression", "dwab"}};
    const Format formats[] = {{"half.exr", half, 2e-3},
                              {"dwab.exr", dwab, 2e-2},
                              {"float.tif", tiff, 1e-6},
                              {"rgbe.hdr", hdr, 1e-2}};
    for (const Format& f : formats) {
        writeImage(dir / f.name, ll, f.options);
        const auto env = ingest(dir / f.name, [] {
            IngestSettings s;
            s.sourceFaceSize = 16;
            return s;
        }());
        EXPECT_EQ(env.report.inputColorSpace, "lin_rec709") << f.name;
        EXPECT_LT(relativeRms(env.cube, reference), f.tolerance) << f.name;
    }
    // 8-bit JPEG decodes from sRGB like PNG.
    WriteOptions jpeg;
    jpeg.format = OIIO::TypeDesc::UINT8;
    writeImage(dir / "grey.jpg", latLongOf(64, 32, [](int, int) { return glm::vec3(128.0f / 255.0f); }),
               jpeg);
    const auto env = ingest(dir / "grey.jpg");
    EXPECT_EQ(env.report.inputColorSpace, "srgb");
    EXPECT_NEAR(env.cube.faces[2].at(3, 3).y, 0.2158605f, 2e-3f);
}

TEST(IngestFile, SingleChannelIsGreyAndAlphaIsIgnored) {
    TempDir dir;
    ImageRGBA ll = latLongOf(64, 32, [](int, int) { return glm::vec3(0.75f); });
    for (glm::vec4& p : ll.pixels)
        p.w = 0.0f;
    WriteOptions grey;
    grey.channels = 1;
    writeImage(dir / "grey.exr", ll, grey);
    const glm::vec4 g = ingest(dir / "grey.exr").cube.faces[4].at(1, 1);
    EXPECT_NEAR(g.x, 0.75f, 1e-6f);
    EXPECT_NEAR(g.z, 0.75f, 1e-6f);
    WriteOptions rgba;
    rgba.channels = 4;
    writeImage(dir / "rgba.exr", ll, rgba);
    EXPECT_NEAR(ingest(dir / "rgba.exr").cube.faces[4].at(1, 1).y, 0.75f, 1e-6f);
    // A transparent PNG keeps its colour: no premultiplication by alpha.
    WriteOptions png;
    png.channels = 4;
    png.format = OIIO::TypeDesc::UINT8;
    ImageRGBA clear = latLongOf(64, 32, [](int, int) { return glm::vec3(128.0f / 255.0f); });
    for (glm::vec4& p : clear.pixels)
        p.w = 0.0f;
    writeImage(dir / "clear.png", clear, png);
    EXPECT_NEAR(ingest(dir / "clear.png").cube.faces[4].at(1, 1).y, 0.2158605f, 1e-5f);
}

// The ACES matrices of data/ocio/config.ocio against OCIO 2.1's built-in transforms (their values as
// printed by OCIO 2.1.2): "UTILITY - ACES-AP1_to_LINEAR-REC709_BFD" and "ACEScg_to_ACES2065-1".
TEST(IngestFile, AcesSpacesMatchOcioBuiltins) {
    struct Case {
        const char* working;
        double m[3][3];
    };
    const Case cases[] = {{"lin_rec709",
                           {{1.7050509453, -0.6217921376, -0.0832588747},
                            {-0.1302564144, 1.1408047676, -0.0105483187},
                            {-0.0240033567, -0.1289689690, 1.1529723406}}},
                          {"aces2065-1",
                           {{0.6954522133, 0.1406787038, 0.1638690680},
                            {0.0447945632, 0.8596711159, 0.0955343172},
                            {-0.0055258824, 0.0040252102, 1.0015007257}}}};
    TempDir dir;
    for (const Case& c : cases)
        for (int primary = 0; primary < 3; ++primary) {
            const ImageRGBA ll = latLongOf(32, 16, [&](int, int) {
                glm::vec3 v(0.0f);
                v[primary] = 1.0f;
                return v;
            });
            writeImage(dir / "p.exr", ll);
            IngestSettings s;
            s.inputColorSpace = "ACEScg"; // an alias in the config
            s.workingColorSpace = c.working;
            const auto env = ingest(dir / "p.exr", s);
            EXPECT_EQ(env.report.inputColorSpace, "acescg");
            EXPECT_EQ(env.report.workingColorSpace, c.working);
            const glm::vec4 p = env.cube.faces[0].at(0, 0);
            // Negative components are repaired (clamped) after the conversion; the others must match.
            for (int r = 0; r < 3; ++r)
                EXPECT_NEAR(p[r], std::max(0.0, c.m[r][primary]), 1e-5)
                    << c.working << " primary " << primary << " row " << r;
        }
}

TEST(IngestFile, AcescgWorkingSpace) {
    TempDir dir;
    writeImage(dir / "red.exr", latLongOf(32, 16, [](int, int) { return glm::vec3(1.0f, 0.0f, 0.0f); }));
    IngestSettings s;
    s.workingColorSpace = "acescg";
    const auto env = ingest(dir / "red.exr", s);
    // Rec.709 red in AP1 (Bradford D65 -> ACES white); see data/ocio/config.ocio for the derivation.
    const glm::vec4 p = env.cube.faces[0].at(0, 0);
    EXPECT_NEAR(p.x, 0.6130974024f, 1e-5f);
    EXPECT_NEAR(p.y, 0.0701937225f, 1e-5f);
    EXPECT_NEAR(p.z, 0.0206155929f, 1e-5f);
    // Luminance is measured in the working space and is the same physical quantity: 0.2126 for pure red.
    EXPECT_NEAR(env.report.maxLuminanceIn, 0.2126f, 2e-4f);
    s.workingColorSpace = "srgb";
    EXPECT_NE(errorOf([&] { ingest(dir / "red.exr", s); }).find("not linear"), std::string::npos);
}

// $OCIO names the config when set (read at each ingest, so this test can set and restore it).
TEST(IngestFile, OcioVariableSelectsTheConfig) {
    TempDir dir;
    writeImage(dir / "one.exr", latLongOf(32, 16, [](int, int) { return glm::vec3(1.0f); }));
    const char* old = std::getenv("OCIO");
    const std::string saved = old ? old : "";
    const fs::path missing = dir / "nowhere.ocio";
    ::setenv("OCIO", missing.c_str(), 1);
    const std::string msg = errorOf([&] { ingest(dir / "one.exr"); });
    if (old)
        ::setenv("OCIO", saved.c_str(), 1);
    else
        ::unsetenv("OCIO");
    EXPECT_NE(msg.find(missing.string()), std::string::npos) << msg;
    EXPECT_NO_THROW(ingest(dir / "one.exr"));
}

TEST(IngestFile, ExrChromaticitiesSelectTheInputSpace) {
    TempDir dir;
    WriteOptions o;
    o.chromaticities = {0.7347f, 0.2653f, 0.0f, 1.0f, 0.0001f, -0.077f, 0.32168f, 0.33767f}; // ACES AP0
    writeImage(dir / "aces.exr", latLongOf(32, 16, [](int, int) { return glm::vec3(1.0f); }), o);
    EXPECT_EQ(ingest(dir / "aces.exr").report.inputColorSpace, "aces2065-1");
    o.chromaticities = {0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f};
    writeImage(dir / "rec709.exr", latLongOf(32, 16, [](int, int) { return glm::vec3(1.0f); }), o);
    EXPECT_EQ(ingest(dir / "rec709.exr").report.inputColorSpace, "lin_rec709");
    o.chromaticities = {0.680f, 0.320f, 0.265f, 0.690f, 0.150f, 0.060f, 0.3127f, 0.3290f}; // Display P3
    writeImage(dir / "p3.exr", latLongOf(32, 16, [](int, int) { return glm::vec3(1.0f); }), o);
    EXPECT_NE(errorOf([&] { ingest(dir / "p3.exr"); }).find((dir / "p3.exr").string()), std::string::npos);
}

TEST(IngestFile, NonImageFileIsAnErrorNamingIt) {
    TempDir dir;
    const fs::path text = dir / "notes.exr";
    std::ofstream(text) << "this is not an image\n";
    const std::string msg = errorOf([&] { ingest(text); });
    EXPECT_NE(msg.find(text.string()), std::string::npos) << msg;
    const std::string missing = errorOf([&] { ingest(dir / "missing.hdr"); });
    EXPECT_NE(missing.find((dir / "missing.hdr").string()), std::string::npos) << missing;
}

TEST(IngestFile, UnknownLayoutIsAnErrorNamingTheFile) {
    TempDir dir;
    const fs::path odd = dir / "odd.exr";
    writeImage(odd, latLongOf(7, 3, [](int, int) { return glm::vec3(1.0f); }));
    const std::string msg = errorOf([&] { ingest(odd); });
    EXPECT_NE(msg.find(odd.string()), std::string::npos) << msg;
    EXPECT_NE(msg.find("7x3"), std::string::npos) << msg;
    EXPECT_NE(msg.find("give the layout"), std::string::npos) << msg; // the way out, without a CLI flag
    EXPECT_EQ(msg.find("--"), std::string::npos) << msg;
    try {
        ingest(odd);
    } catch (const ibl::SettingError& e) {
        EXPECT_EQ(e.setting(), "layout");
    }
    // A layout the size cannot hold is an error too, not a crash or a guess.
    IngestSettings s;
    s.layout = EnvLayout::HorizontalCross;
    EXPECT_NE(errorOf([&] { ingest(odd, s); }).find(odd.string()), std::string::npos);
    const fs::path thin = dir / "thin.exr"; // 40:1 is no environment map
    writeImage(thin, latLongOf(80, 2, [](int, int) { return glm::vec3(1.0f); }));
    s.layout = EnvLayout::LatLong;
    EXPECT_NE(errorOf([&] { ingest(thin, s); }).find("80x2"), std::string::npos);
}

// ---------------------------------------------------------------------------------------------------
// Cube layouts. The test's own description of each layout: where face f sits, in face-size units, and
// whether it is turned by 180 degrees (ingest.h documents the same arrangement).

struct Placement {
    int col, row;
    bool turned;
};

Placement placement(EnvLayout layout, int f) {
    static const Placement hcross[6] = {{2, 1, false}, {0, 1, false}, {1, 0, false},
                                        {1, 2, false}, {1, 1, false}, {3, 1, false}};
    static const Placement vcross[6] = {{2, 1, false}, {0, 1, false}, {1, 0, false},
                                        {1, 2, false}, {1, 1, false}, {1, 3, true}};
    switch (layout) {
    case EnvLayout::HorizontalCross:
        return hcross[f];
    case EnvLayout::VerticalCross:
        return vcross[f];
    case EnvLayout::HorizontalStrip:
        return {f, 0, false};
    default:
        return {0, f, false};
    }
}

// An image in `layout` whose face texels hold directionColor of their direction; the rest is black.
ImageRGBA layoutImage(EnvLayout layout, int n) {
    const int cols = layout == EnvLayout::HorizontalCross   ? 4
                     : layout == EnvLayout::VerticalCross   ? 3
                     : layout == EnvLayout::HorizontalStrip ? 6
                                                            : 1;
    const int rows = layout == EnvLayout::HorizontalCross   ? 3
                     : layout == EnvLayout::VerticalCross   ? 4
                     : layout == EnvLayout::HorizontalStrip ? 1
                                                            : 6;
    ImageRGBA im(cols * n, rows * n);
    for (int f = 0; f < 6; ++f) {
        const Placement p = placement(layout, f);
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const int x = p.turned ? n - 1 - i : i, y = p.turned ? n - 1 - j : j;
                im.at(p.col * n + x, p.row * n + y) =
                    glm::vec4(directionColor(texelDirection(f, i, j, n)), 1.0f);
            }
    }
    return im;
}

// The crosses must be true unfoldings: across every seam inside the cross the image is continuous.
TEST(IngestLayouts, CrossesAreUnfoldings) {
    const int n = 32;
    for (EnvLayout layout : {EnvLayout::HorizontalCross, EnvLayout::VerticalCross}) {
        const ImageRGBA im = layoutImage(layout, n);
        int seams = 0;
        for (int a = 0; a < 6; ++a)
            for (int b = 0; b < 6; ++b) {
                const Placement pa = placement(layout, a), pb = placement(layout, b);
                const bool right = pb.col == pa.col + 1 && pb.row == pa.row;
                const bool below = pb.row == pa.row + 1 && pb.col == pa.col;
                if (!right && !below) continue;
                ++seams;
                double worst = 0.0;
                for (int k = 0; k < n; ++k) {
                    const glm::vec4 p =
                        right ? im.at(pb.col * n - 1, pa.row * n + k) : im.at(pa.col * n + k, pb.row * n - 1);
                    const glm::vec4 q =
                        right ? im.at(pb.col * n, pa.row * n + k) : im.at(pa.col * n + k, pb.row * n);
                    worst = std::max(worst, double(glm::length(glm::vec3(p - q))));
                }
                EXPECT_LT(worst, 0.06)
                    << ibl::layoutName(layout) << " seam between faces " << a << " and " << b;
            }
        EXPECT_EQ(seams, 5) << ibl::layoutName(layout);
    }
}

TEST(IngestLayouts, CrossesAndStripsRoundTrip) {
    TempDir dir;
    const int n = 24;
    for (EnvLayout layout : {EnvLayout::HorizontalCross, EnvLayout::VerticalCross, EnvLayout::HorizontalStrip,
                             EnvLayout::VerticalStrip}) {
        const fs::path file = dir / (std::string(ibl::layoutName(layout)) + ".exr");
        writeImage(file, layoutImage(layout, n));
        const auto env = ingest(file); // detected from the aspect ratio
        EXPECT_EQ(env.report.layout, layout);
        ASSERT_EQ(env.cube.faceSize, n);
        const double worst = worstDirectionColorError(env.cube);
        EXPECT_LT(worst, 1e-6) << ibl::layoutName(layout);
    }
}

TEST(IngestLayouts, SixFilesRoundTripAndResampleByArea) {
    TempDir dir;
    const int n = 16;
    const ImageRGBA strip = layoutImage(EnvLayout::HorizontalStrip, n);
    std::vector<fs::path> files;
    for (int f = 0; f < 6; ++f) {
        ImageRGBA face(n, n);
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                face.at(i, j) = strip.at(f * n + i, j);
        files.push_back(dir / ("face" + std::to_string(f) + ".exr"));
        writeImage(files.back(), face);
    }
    IngestSettings s;
    s.layout = EnvLayout::SixFiles;
    const auto env = ibl::ingestEnvironment(files, s);
    EXPECT_NEAR(env.cube.faces[3].at(5, 9).x, directionColor(texelDirection(3, 5, 9, n)).x, 1e-6f);
    // Downsampling by area keeps the energy exactly.
    s.sourceFaceSize = 5;
    const auto small = ibl::ingestEnvironment(files, s);
    EXPECT_NEAR(cubeEnergy(small.cube).x / cubeEnergy(env.cube).x, 1.0, 1e-6);
    // Six files need six files.
    EXPECT_THROW(ibl::ingestEnvironment({files[0]}, s), ibl::Error);
}

TEST(IngestLayouts, CubeFaceMetadataSelectsExrCube) {
    TempDir dir;
    const ImageRGBA im = layoutImage(EnvLayout::VerticalStrip, 8);
    WriteOptions o;
    o.attributes = {{"textureformat", "CubeFace Environment"}}; // OIIO writes OpenEXR's envmap = cube
    writeImage(dir / "cube.exr", im, o);
    writeImage(dir / "strip.exr", im);
    EXPECT_EQ(ingest(dir / "cube.exr").report.layout, EnvLayout::ExrCube);
    EXPECT_EQ(ingest(dir / "strip.exr").report.layout, EnvLayout::VerticalStrip);
}

// An OpenEXR cube map whose pixels hold the colour of their ImfEnvmap direction ingests to our faces.
TEST(IngestLayouts, ExrCubeFollowsImfEnvmap) {
    TempDir dir;
    const int m = 32;
    ImageRGBA im(m, 6 * m);
    const IMATH_NAMESPACE::Box2i window(IMATH_NAMESPACE::V2i(0, 0), IMATH_NAMESPACE::V2i(m - 1, 6 * m - 1));
    for (int f = 0; f < 6; ++f)
        for (int py = 0; py < m; ++py)
            for (int px = 0; px < m; ++px) {
                const IMATH_NAMESPACE::V2f pif{float(px), float(py)};
                const auto d = Imf::CubeMap::direction(Imf::CubeMapFace(f), window, pif);
                const auto pos = Imf::CubeMap::pixelPosition(Imf::CubeMapFace(f), window, pif);
                im.at(int(pos.x), int(pos.y)) = glm::vec4(directionColor(glm::dvec3(d.x, d.y, d.z)), 1.0f);
            }
    WriteOptions o;
    o.attributes = {{"textureformat", "CubeFace Environment"}};
    writeImage(dir / "cube.exr", im, o);
    IngestSettings s;
    for (int n : {m, 16}) {
        s.sourceFaceSize = n;
        const auto env = ingest(dir / "cube.exr", s);
        EXPECT_EQ(env.report.layout, EnvLayout::ExrCube);
        const double worst = worstDirectionColorError(env.cube);
        EXPECT_LT(worst, 0.03) << "face size " << n; // within a texel's colour change; a flip is ~1
    }
}

TEST(IngestLayouts, CubeInputRotation) {
    TempDir dir;
    const int n = 32;
    writeImage(dir / "hcross.exr", layoutImage(EnvLayout::HorizontalCross, n));
    IngestSettings s;
    s.rotateDegrees = 90.0f;
    const auto env = ingest(dir / "hcross.exr", s);
    double worst = 0.0;
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const glm::dvec3 d = texelDirection(f, i, j, n);
                const glm::vec3 expected = directionColor(glm::dvec3(-d.z, d.y, d.x)); // R(-90 deg) d
                worst =
                    std::max(worst, double(glm::length(glm::vec3(env.cube.faces[f].at(i, j)) - expected)));
            }
    EXPECT_LT(worst, 0.03);
}

// ---------------------------------------------------------------------------------------------------
// The shared data set (../shared/data): skipped when it is not there.

const fs::path kShared = fs::path(IBLBAKE_SHARED_DIR) / "data";

#define REQUIRE_FILE(path)                                                                                   \
    do {                                                                                                     \
        if (!fs::exists(path)) GTEST_SKIP() << (path).string() << " is not present";                         \
    } while (0)

TEST(IngestShared, OrientationFilesIngestToTheSameCube) {
    const fs::path ll = kShared / "orientation/OrientationLatLong.exr",
                   cube = kShared / "orientation/OrientationCube.exr";
    REQUIRE_FILE(ll);
    REQUIRE_FILE(cube);
    IngestSettings s;
    s.sourceFaceSize = 128;
    const auto a = ingest(ll, s), b = ingest(cube, s);
    EXPECT_EQ(a.report.layout, EnvLayout::LatLong);
    EXPECT_EQ(b.report.layout, EnvLayout::ExrCube);
    const double rms = relativeRms(a.cube, b.cube);
    RecordProperty("relative_rms_128", std::to_string(rms));
    EXPECT_LT(rms, 0.02);
}

// Each of the six axis figures in the orientation maps has its origin on an axis and arms that point
// toward the positive world axes. Checked in the lat-long file itself through docs/conventions.md's mapping
// (+X at u = 0.25, zenith on the first scanline, ...), then in the ingested cubes of both files.
TEST(IngestShared, OrientationLabelsLandWhereDesignSays) {
    const fs::path ll = kShared / "orientation/OrientationLatLong.exr",
                   cubeFile = kShared / "orientation/OrientationCube.exr";
    REQUIRE_FILE(ll);
    REQUIRE_FILE(cubeFile);
    auto in = OIIO::ImageInput::open(ll.string());
    ASSERT_TRUE(in);
    const OIIO::ImageSpec spec = in->spec();
    std::vector<float> px(std::size_t(spec.width) * spec.height * spec.nchannels);
    ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, px.data()));
    // Darkest / mean luminance over the 3x3 pixels around a direction.
    auto rawLum = [&](const glm::dvec3& d, bool darkest) {
        const ibl::float2 uv = ibl::latlongFromDirection(ibl::vec3(d));
        // The file carries envmap = latlong: OpenEXR's placement.
        const int x = ibl::latLongPixelAt(LatLongPixels::OpenExr, uv.x, spec.width),
                  y = ibl::latLongPixelAt(LatLongPixels::OpenExr, uv.y, spec.height);
        double result = darkest ? 1e30 : 0.0;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const int xx = (x + dx + spec.width) % spec.width,
                          yy = std::clamp(y + dy, 0, spec.height - 1);
                const float* p = &px[(std::size_t(yy) * spec.width + xx) * spec.nchannels];
                const double l = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
                result = darkest ? std::min(result, l) : result + l / 9.0;
            }
        return result;
    };
    // Darkest / mean luminance over the 3x3 texels around a direction.
    auto cubeLum = [](const CubeMap& c, const glm::dvec3& d, bool darkest) {
        const ibl::CubeCoord cc = ibl::cubeCoordFromDirection(ibl::vec3(d));
        const int n = c.faceSize, i = std::min(int(cc.s * n), n - 1), j = std::min(int(cc.t * n), n - 1);
        double result = darkest ? 1e30 : 0.0;
        for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di) {
                const double l = luminance(
                    c.faces[cc.face].at(std::clamp(i + di, 0, n - 1), std::clamp(j + dj, 0, n - 1)));
                result = darkest ? std::min(result, l) : result + l / 9.0;
            }
        return result;
    };
    IngestSettings s;
    s.sourceFaceSize = 256;
    const CubeMap fromLatLong = ingest(ll, s).cube, fromCube = ingest(cubeFile, s).cube;

    const glm::dvec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const char* names[6] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
    for (int f = 0; f < 6; ++f) {
        const glm::dvec3 centre = axes[f / 2] * (f % 2 ? -1.0 : 1.0);
        for (int e = 0; e < 3; ++e) {
            if (e == f / 2) continue;
            const glm::dvec3 arm = glm::normalize(centre + 0.25 * axes[e]);
            const glm::dvec3 away = glm::normalize(centre - 0.25 * axes[e]);
            const std::string what = std::string(names[f]) + " figure, arm toward +" + "XYZ"[e];
            EXPECT_LT(rawLum(arm, true), 0.1) << what << " (lat-long file)";
            EXPECT_LT(cubeLum(fromLatLong, arm, true), 0.25) << what << " (cube from lat-long)";
            EXPECT_LT(cubeLum(fromCube, arm, true), 0.25) << what << " (cube from cube file)";
            if (e == 1) continue; // below a side figure's origin sits its label: not blank
            EXPECT_GT(rawLum(away, false), 0.5) << what << ", opposite side (lat-long file)";
            EXPECT_GT(cubeLum(fromLatLong, away, false), 0.5)
                << what << ", opposite side (cube from lat-long)";
            EXPECT_GT(cubeLum(fromCube, away, false), 0.5) << what << ", opposite side (cube from cube file)";
        }
    }
}

struct HdriFacts {
    const char* name;
    EnvLayout layout;
    int width, height;
    double maxLuminance; // SOURCES.md "Lum. max"
    double sphereMean;   // SOURCES.md "Sphere mean"
};

TEST(IngestShared, EveryHdriReads) {
    const HdriFacts facts[] = {
        {"rooitou_park_1k.hdr", EnvLayout::LatLong, 1024, 512, 64889.75, 0.7557},
        {"potsdamer_platz_1k.hdr", EnvLayout::LatLong, 1024, 512, 10.94345, 0.5583},
        {"studio_small_03_1k.hdr", EnvLayout::LatLong, 1024, 512, 3351.52, 2.2193},
        {"venice_sunset_1k.hdr", EnvLayout::LatLong, 1024, 512, 2090.53, 0.4979},
        {"KernerEnvLatLong.exr", EnvLayout::LatLong, 1024, 512, 1678.0, 0.1860},
        {"KernerEnvCube.exr", EnvLayout::ExrCube, 256, 1536, 1657.0, 0.1859},
        {"blender_world_sunrise.exr", EnvLayout::LatLong, 1024, 512, 32961.62, 0.6485},
    };
    int found = 0;
    for (const HdriFacts& h : facts) {
        const fs::path file = kShared / "hdri" / h.name;
        if (!fs::exists(file)) continue;
        ++found;
        const auto env = ingest(file);
        EXPECT_EQ(env.report.layout, h.layout) << h.name;
        EXPECT_EQ(env.report.width, h.width) << h.name;
        EXPECT_EQ(env.report.height, h.height) << h.name;
        EXPECT_EQ(env.report.inputColorSpace, "lin_rec709") << h.name;
        EXPECT_EQ(env.report.nanRepaired + env.report.infRepaired, 0u) << h.name;
        EXPECT_NEAR(env.report.maxLuminanceIn / h.maxLuminance, 1.0, 1e-3) << h.name;
        double sum = 0.0;
        for (int f = 0; f < 6; ++f)
            for (int j = 0; j < env.cube.faceSize; ++j)
                for (int i = 0; i < env.cube.faceSize; ++i)
                    sum += luminance(env.cube.faces[f].at(i, j)) *
                           ibl::cubeTexelSolidAngle(i, j, env.cube.faceSize);
        const double mean = sum / (4.0 * kPi);
        RecordProperty(std::string("sphere_mean_") + h.name, std::to_string(mean));
        EXPECT_NEAR(mean / h.sphereMean, 1.0, 5e-3) << h.name;
        if (std::string(h.name) == "blender_world_sunrise.exr") { // SOURCES.md: 358 negative B values (DWAB)
            EXPECT_EQ(env.report.negativeRepaired, 358u);
        }
    }
    if (found == 0)
        GTEST_SKIP() << kShared / "hdri"
                     << " holds none of the shared HDRIs";
}

TEST(IngestShared, KernerLatLongAndCubeAgree) {
    const fs::path ll = kShared / "hdri/KernerEnvLatLong.exr", cube = kShared / "hdri/KernerEnvCube.exr";
    REQUIRE_FILE(ll);
    REQUIRE_FILE(cube);
    IngestSettings s;
    s.sourceFaceSize = 32;
    const auto a = ingest(ll, s), b = ingest(cube, s);
    const double rms = relativeRms(a.cube, b.cube);
    RecordProperty("relative_rms_32", std::to_string(rms));
    EXPECT_LT(rms, 0.05);
    // The sun: SOURCES.md gives (-0.899, 0.352, 0.262) for the lat-long's peak pixel.
    const Texel ta = brightest(a.cube), tb = brightest(b.cube);
    EXPECT_EQ(ta.face, tb.face);
    EXPECT_LE(std::abs(ta.i - tb.i), 2);
    EXPECT_LE(std::abs(ta.j - tb.j), 2);
    const glm::dvec3 sun(-0.899, 0.352, 0.262);
    EXPECT_LT(angleBetween(texelDirection(ta.face, ta.i, ta.j, 32), sun), 2.0 * 2.0 / 32);
    EXPECT_LT(angleBetween(texelDirection(tb.face, tb.i, tb.j, 32), sun), 2.0 * 2.0 / 32);
}

} // namespace

namespace {

// RGBA of `file` as OpenImageIO reads it (level 0 of the first subimage; A = 1 when it has none).
std::vector<glm::vec4> readWithOiio(const fs::path& file, OIIO::ImageSpec& spec) {
    auto in = OIIO::ImageInput::open(file.string());
    EXPECT_TRUE(in) << file;
    if (!in) return {};
    spec = in->spec();
    std::vector<float> values(std::size_t(spec.width) * spec.height * spec.nchannels);
    EXPECT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, values.data())) << file;
    const int r = spec.channelindex("R"), g = spec.channelindex("G"), b = spec.channelindex("B");
    std::vector<glm::vec4> rgba(std::size_t(spec.width) * spec.height);
    for (std::size_t i = 0; i < rgba.size(); ++i) {
        const float* p = &values[i * std::size_t(spec.nchannels)];
        rgba[i] = glm::vec4(p[r], p[g], p[b], spec.alpha_channel >= 0 ? p[spec.alpha_channel] : 1.0f);
    }
    return rgba;
}

} // namespace

// The readers that replace OpenImageIO for OpenEXR and Radiance files (image_source.h) read every pixel
// bit for bit as OpenImageIO does, and report the metadata ingest decides by the same way.
TEST(ImageSources, MatchOpenImageIOOnRealFiles) {
    std::vector<fs::path> files = {ibl::test::kSampleHdri};
    for (const char* name : ibl::test::kSharedHdris)
        if (fs::exists(ibl::test::hdriPath(name))) files.push_back(ibl::test::hdriPath(name));
    for (const fs::path& file : files) {
        OIIO::ImageSpec spec;
        const std::vector<glm::vec4> expected = readWithOiio(file, spec);
        const ibl::ingest::RawImage raw = ibl::ingest::readImage(file, nullptr, true);
        ASSERT_EQ(raw.pixels.width, spec.width) << file;
        ASSERT_EQ(raw.pixels.height, spec.height) << file;
        ASSERT_EQ(raw.pixels.pixels.size(), expected.size()) << file;
        std::size_t differing = 0;
        for (std::size_t i = 0; i < expected.size(); ++i)
            differing += std::memcmp(&raw.pixels.pixels[i], &expected[i], sizeof(glm::vec4)) != 0;
        EXPECT_EQ(differing, 0u) << file;
        EXPECT_EQ(raw.textureFormat, spec.get_string_attribute("textureformat")) << file;
        EXPECT_EQ(raw.upDirection, spec.get_string_attribute("oiio:updirection")) << file;
        EXPECT_EQ(raw.colorSpace, spec.get_string_attribute("oiio:ColorSpace")) << file;
        EXPECT_EQ(raw.hasAlpha, spec.alpha_channel >= 0) << file;
    }
}

namespace {

// Radiance run-length encoding of one scanline (Ward, Graphics Gems II): per channel, runs of 3 or more
// equal bytes as (128 + count, byte), the rest as (count, literal bytes), counts up to 127.
void appendEncodedScanline(std::string& out, const std::vector<std::uint8_t>& rgbe, int width) {
    out += {char(2), char(2), char(width >> 8), char(width & 0xff)};
    for (int channel = 0; channel < 4; ++channel) {
        auto at = [&](int x) { return rgbe[std::size_t(4 * x + channel)]; };
        for (int x = 0; x < width;) {
            int run = 1;
            while (x + run < width && run < 127 && at(x + run) == at(x))
                ++run;
            if (run >= 3) {
                out += {char(128 + run), char(at(x))};
                x += run;
                continue;
            }
            int literal = 1;
            while (x + literal < width && literal < 127 &&
                   !(x + literal + 2 < width && at(x + literal) == at(x + literal + 1) &&
                     at(x + literal) == at(x + literal + 2)))
                ++literal;
            out += char(literal);
            for (int k = 0; k < literal; ++k)
                out += char(at(x + k));
            x += literal;
        }
    }
}

} // namespace

// Every mantissa at every exponent, flat and run-length encoded: the reader's values are ldexp(mantissa,
// exponent - 136) (0 at exponent 0) bit for bit, as rgbe.c and OpenImageIO decode.
TEST(ImageSources, RadianceDecodesEveryExponentAsLdexp) {
    constexpr int kSize =
        256; // pixel (x, y): mantissas x, x + 1, x + 2 (never the run marker 1, 1, 1), exponent y
    std::vector<std::vector<std::uint8_t>> rows;
    for (int y = 0; y < kSize; ++y) {
        std::vector<std::uint8_t> row;
        for (int x = 0; x < kSize; ++x)
            row.insert(row.end(),
                       {std::uint8_t(x), std::uint8_t(x + 1), std::uint8_t(x + 2), std::uint8_t(y)});
        rows.push_back(row);
    }
    const std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 256 +X 256\n";
    std::string flat = header, encoded = header;
    for (const auto& row : rows) {
        flat.append(reinterpret_cast<const char*>(row.data()), row.size());
        appendEncodedScanline(encoded, row, kSize);
    }
    TempDir dir;
    for (const auto& [name, bytes] : {std::pair{"flat.hdr", flat}, std::pair{"encoded.hdr", encoded}}) {
        std::ofstream(dir / name, std::ios::binary) << bytes;
        const ibl::ingest::RawImage raw = ibl::ingest::readImage(dir / name);
        ASSERT_EQ(raw.pixels.width, kSize);
        ASSERT_EQ(raw.pixels.height, kSize);
        std::size_t differing = 0;
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x)
                for (int c = 0; c < 3; ++c) {
                    const std::uint8_t mantissa = rows[std::size_t(y)][std::size_t(4 * x + c)];
                    const float expected = y == 0 ? 0.0f : std::ldexp(float(mantissa), y - 136);
                    const float got = raw.pixels.at(x, y)[c];
                    differing += std::memcmp(&got, &expected, sizeof(float)) != 0;
                }
        EXPECT_EQ(differing, 0u) << name;
        // Kept as stored, the pixels are the file's bytes, and decode to the floats above.
        ibl::ingest::RawImage kept = ibl::ingest::readImage(dir / name, nullptr, false, true);
        ASSERT_EQ(kept.rgbe.pixels.size(), std::size_t(kSize) * kSize);
        EXPECT_TRUE(kept.pixels.pixels.empty());
        for (int y = 0; y < kSize; ++y)
            ASSERT_EQ(std::memcmp(&kept.rgbe.pixels[std::size_t(y) * kSize], rows[std::size_t(y)].data(),
                                  4 * kSize),
                      0)
                << name << " row " << y;
        ibl::ingest::decodeKeptRgbe(kept);
        EXPECT_TRUE(kept.rgbe.pixels.empty());
        ASSERT_EQ(kept.pixels.pixels.size(), raw.pixels.pixels.size());
        EXPECT_EQ(std::memcmp(kept.pixels.pixels.data(), raw.pixels.pixels.data(),
                              raw.pixels.pixels.size() * sizeof(glm::vec4)),
                  0)
            << name;
    }
}

// A Radiance lat-long is resampled from its RGBE bytes as stored (rgbe.h): the cube has the bits of the
// one resampled from the decoded floats, with and without the symmetric geometry, in both pixel
// placements, rotated, and at an odd face size.
TEST(ImageSources, RadianceKeptAsStoredResamplesToTheDecodedBits) {
    const ibl::ingest::RawImage kept = ibl::ingest::readImage(ibl::test::kSampleHdri, nullptr, false, true);
    ibl::ingest::RawImage decoded = kept;
    ibl::ingest::decodeKeptRgbe(decoded);
    EXPECT_EQ(ibl::ingest::maxLuminance(kept.rgbe, ibl::kRec709Luminance),
              ibl::ingest::maxLuminance(decoded.pixels, ibl::kRec709Luminance));
    struct Case {
        int faceSize;
        LatLongPixels placement;
        double rotate;
        bool symmetry;
    };
    for (const Case& c :
         {Case{32, LatLongPixels::Centre, 0.0, true}, Case{32, LatLongPixels::Centre, 0.0, false},
          Case{32, LatLongPixels::OpenExr, 0.0, true}, Case{32, LatLongPixels::Centre, 0.7, true},
          Case{31, LatLongPixels::Centre, 0.0, true}})
        EXPECT_TRUE(sameBits(ibl::ingest::resampleLatLongToCubeRotated(kept.rgbe, c.faceSize, c.placement,
                                                                       c.rotate, c.symmetry),
                             ibl::ingest::resampleLatLongToCubeRotated(
                                 decoded.pixels, c.faceSize, c.placement, c.rotate, false, c.symmetry)))
            << c.faceSize << " " << int(c.placement) << " " << c.rotate << " " << c.symmetry;
}

// Ingest of a Radiance file equals that of an OpenEXR file holding its decoded floats, bit for bit, where
// the RGBE pixels go to the resampling as stored (a lat-long in its own colour space) and where they are
// decoded first (a strip of faces; a colour conversion).
TEST(ImageSources, RadianceIngestsAsItsDecodedFloats) {
    TempDir dir;
    const ImageRGBA latLong =
        latLongOf(64, 32, [](int x, int y) { return glm::vec3(0.5f + x / 7.0f, 2.0f + y, 0.25f + x * y); });
    const ImageRGBA strip =
        latLongOf(16, 96, [](int x, int y) { return glm::vec3(0.5f + x / 7.0f, 2.0f + y, 0.25f + x * y); });
    for (const auto& [name, image] : {std::pair{"latlong", latLong}, std::pair{"strip", strip}}) {
        const fs::path hdr = dir / (std::string(name) + ".hdr"), exr = dir / (std::string(name) + ".exr");
        writeImage(hdr, image);
        writeImage(exr, ibl::ingest::readImage(hdr).pixels);
        for (const char* working : {"lin_rec709", "acescg"}) {
            IngestSettings settings;
            settings.workingColorSpace = working;
            const ibl::SourceEnvironment fromHdr = ingest(hdr, settings), fromExr = ingest(exr, settings);
            EXPECT_EQ(fromHdr.report.layout, fromExr.report.layout) << name;
            EXPECT_EQ(fromHdr.report.maxLuminanceIn, fromExr.report.maxLuminanceIn) << name << " " << working;
            EXPECT_TRUE(sameBits(fromHdr.cube, fromExr.cube)) << name << " " << working;
        }
    }
}
