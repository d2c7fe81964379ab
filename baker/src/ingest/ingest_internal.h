// Pieces of the ingest front end shared between its translation units (not part of the public API).
#pragma once

#include "iblbake/baker/ingest.h"
#include "iblbake/core/cubemap.h"
#include "iblbake/core/image.h"
#include "image_source.h"
#include "rgbe.h"

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <cube.h>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace ibl::ingest {

// Face-plane frame of one of our cube faces: the direction through face-plane point (a, b), with
// a = 2s - 1 and b = 2t - 1 of kernels/cube.h, is o + a u + b v (o, u, v orthonormal axes).
struct FaceFrame {
    glm::dvec3 o, u, v;
    glm::dvec3 at(double a, double b) const { return o + a * u + b * v; }
};

inline FaceFrame faceFrame(int face) {
    const vec3 c = cubeFaceDirection(face, 0.5f, 0.5f);
    const vec3 pu = cubeFaceDirection(face, 1.0f, 0.5f);
    const vec3 pv = cubeFaceDirection(face, 0.5f, 1.0f);
    return {glm::dvec3(c), glm::dvec3(pu - c), glm::dvec3(pv - c)};
}

// ---- reading (read_image.cpp) ----
struct RawImage {
    std::string file;
    ImageRGBA pixels;                  // R, G, B of the file's level 0 (grey replicated), A (1 if not read)
    ImageRGBE rgbe;                    // a Radiance file's pixels as stored, when read so (`pixels` then
                                       // holds the size only)
    bool hasAlpha = false;             // A was read from the file's alpha channel
    bool unassociatedAlpha = false;    // the file's colour is not premultiplied by its alpha (PNG, some TIFF)
    std::string colorSpace;            // the format's colour space name ("Linear" for OpenEXR), "" if none
    std::vector<float> chromaticities; // EXR chromaticities (8 values) if present
    std::string textureFormat;         // "LatLong Environment" or "CubeFace Environment" (OpenEXR envmap)
    std::string upDirection;           // "y" for an OpenEXR lat-long envmap, else "oiio:updirection"
    bool integerPixels = false;        // stored as integers (8-bit PNG/JPEG, 16-bit TIFF...): display-encoded
};

// Reads level 0 of the first subimage. Throws ibl::Error "<file>: ..." when it cannot, when it is no
// regular file, or when its header claims more pixels than limits::maxImagePixels(). `checkHeader`, when
// given, sees the image with its size and metadata before any pixel is read (pixels.pixels still empty),
// so that a size that cannot work (a layout that does not fit) is refused without reading the file. With
// `readAlpha`, the file's alpha channel (the format's own, else one named "A"), if it has one, is read into
// A as stored. OpenEXR and Radiance files are read without OpenImageIO (image_source.h). With `keepRgbe`, a
// Radiance file's pixels are kept as stored, in `rgbe` (a quarter of the memory; rgbe.h).
RawImage readImage(const std::filesystem::path& file,
                   const std::function<void(const RawImage&)>& checkHeader = nullptr, bool readAlpha = false,
                   bool keepRgbe = false);
// An image file whose header has been read and checked (readImage is openImage, then readPixels).
struct OpenedImage {
    RawImage raw;                        // metadata and size; no pixels yet
    std::unique_ptr<ImageSource> source; // its decoder
    std::array<int, 3> rgb{};            // the file's channels read as R, G, B (one channel read as grey)
    int alpha = -1;                      // the file's channel read as A, -1 for none (A = 1)
};
// readImage's first half: the file opened, its header checked (`checkHeader`, the pixel limit), the
// channels picked. Throws as readImage does.
OpenedImage openImage(const std::filesystem::path& file,
                      const std::function<void(const RawImage&)>& checkHeader = nullptr,
                      bool readAlpha = false);
// readImage's second half: every pixel into image.raw (`keepRgbe` as readImage's).
void readPixels(OpenedImage& image, bool keepRgbe = false);
// Rows [y0, y1) of an opened image as RGBA (A = 1 when no alpha is read) into `out`, width pixels a row;
// `strip` is scratch. Rows are asked for as ImageSource::readRows allows. `written`, when given, is called on
// every range of pixels once they are complete, from parallel tasks, while the range is in cache.
void readRgbaRows(OpenedImage& image, int y0, int y1, glm::vec4* out, std::vector<float>& strip,
                  const std::function<void(glm::vec4*, std::size_t)>& written = nullptr);

// Decodes the RGBE pixels readImage kept into `pixels` (and frees them); nothing when there are none.
void decodeKeptRgbe(RawImage& image);

// Throws ibl::Error "<name>: WxH is N pixels, more than the limit of M (IBLBAKE_MAX_IMAGE_PIXELS)" when a
// width x height image (both >= 1) is over limits::maxImagePixels().
void checkPixelLimit(const std::string& name, std::uint64_t width, std::uint64_t height);

// The text metadata of an image file (OpenEXR string attributes; what OpenImageIO reports for other
// formats; none for Radiance). Throws ibl::Error "<file>: ..." when it cannot be opened.
std::vector<std::pair<std::string, std::string>> readStringAttributes(const std::filesystem::path& file);

// Walks an OpenEXR file's header(s) before OpenEXR opens it, refusing
// (ibl::Error "<name>: ...") an attribute larger than the rest of the file, a string vector or preview
// claiming more than its attribute holds, a chunkCount the file cannot hold and a dataWindow over the
// pixel limit: OpenEXR sizes memory from each of these while it reads the header (exr_header.cpp).
void checkExrHeader(const std::filesystem::path& file, const std::string& name);

// A visibility mask's channel R as `image`'s A (IngestSettings::visibilityMask): the colour becomes straight
// (unassociatedAlpha). Throws ibl::Error naming the mask when its size is not the image's.
void takeVisibilityMask(RawImage& image, const RawImage& mask);

// ---- layout (layout.cpp) ----
// The layout of a single image: `requested` if not Auto (checked against the size), else detected from
// metadata and aspect ratio. Throws ibl::Error naming the file when it cannot tell or the size does not fit.
EnvLayout resolveLayout(const RawImage& image, EnvLayout requested);
// The placement of a lat-long image's pixels: `requested` unless Auto, else OpenExr when the file carries
// OpenEXR's envmap = latlong attribute (OIIO textureformat "LatLong Environment"), else Centre.
LatLongPixels resolveLatLongPixels(const RawImage& image, LatLongPixels requested);

// ---- colour (color.cpp) ----
// The input colour space: `requested` if given, else from metadata; returned as the config's name.
std::string resolveInputColorSpace(const RawImage& image, const std::string& requested);
// The config's own name of a colour space given by name or alias, "" if it has none.
std::string colorSpaceName(const std::string& nameOrAlias);
// Whether converting from -> to changes nothing (convertColor would return false); throws as it does.
bool isIdentityConversion(const std::string& from, const std::string& to, const std::string& file);
// Converts in place (RGB; alpha untouched); false when the conversion is the identity and nothing was done.
// Throws ibl::Error naming `file` on OCIO errors.
bool convertColor(ImageRGBA& image, const std::string& from, const std::string& to, const std::string& file);
// Luminance weights of a linear colour space: the Y row of its RGB -> XYZ (via lin_rec709 in the config).
glm::dvec3 luminanceWeights(const std::string& linearSpace);
// Path of the OCIO config in use: $OCIO if set, else the one shipped in data/ocio.
std::string ocioConfigPath();

// ---- sanitize (sanitize.cpp) ----
struct RepairCounts {
    std::uint64_t nan = 0, inf = 0, negative = 0;
    RepairCounts operator+(const RepairCounts& o) const {
        return {nan + o.nan, inf + o.inf, negative + o.negative};
    }
};
// NaN -> 0, +Inf -> largest finite value of the image (65504 if none), -Inf and negatives -> 0 (RGB only).
RepairCounts sanitize(ImageRGBA& image);
// convertColor on an image sanitize() has repaired, then the repair of what the conversion made (a wide-gamut
// source gives negatives in a smaller space); none when no conversion ran, as a repaired image that nothing
// changed has nothing left to repair.
RepairCounts convertColorRepaired(ImageRGBA& image, const std::string& from, const std::string& to,
                                  const std::string& file);
float maxLuminance(const ImageRGBA& image, const glm::dvec3& weights);
// sanitize() and then maxLuminance() of `count` pixels in one pass (a streamed ingest's, over pixels just
// decoded), where they hold no +Inf: its repair takes the whole image's largest finite value, so +Inf values
// are left as they are and counted in plusInf (the caller then reads the image whole).
struct FiniteRepair {
    RepairCounts counts;
    std::uint64_t plusInf = 0;
    float maxLuminance = 0.0f;
};
FiniteRepair repairFinite(glm::vec4* pixels, std::size_t count, const glm::dvec3& weights);
float maxLuminance(const ImageRGBE& image, const glm::dvec3& weights);
struct AlphaRepairCounts {
    std::uint64_t nan = 0, negative = 0, overOne = 0;
    AlphaRepairCounts operator+(const AlphaRepairCounts& o) const {
        return {nan + o.nan, negative + o.negative, overOne + o.overOne};
    }
};
// Alpha (IngestReport::hasAlpha): NaN and negatives -> RGBA 0, over 1 -> 1 (colour kept), per pixel.
AlphaRepairCounts sanitizeAlpha(ImageRGBA& image);
// Whether any pixel's A is not 1.
bool hasAlphaBelowOne(const ImageRGBA& image);
// Colour of unassociated alpha premultiplied by it (after the colour conversion, which needs it straight).
void premultiplyAlpha(ImageRGBA& image);

// ---- cube faces (faces_to_cube.cpp) ----
// One face of a cube-like input, already in our face's orientation: cell (c, r) spans face-plane
// coordinates [edgesA[c], edgesA[c+1]] x [edgesB[r], edgesB[r+1]] where a = 2s - 1, b = 2t - 1 of
// kernels/cube.h. The edges increase from -1 to 1 and the cells cover the face exactly.
struct SourceFace {
    int cols = 0, rows = 0;
    std::vector<glm::vec3> values; // row-major, rows along b
    std::vector<float> alpha;      // the same cells' A, empty when the input has no alpha
    std::vector<double> edgesA, edgesB;
};
using SourceFaces = std::array<SourceFace, 6>;

// Faces of a strip, cross or six-file input (uniform cells, faces already in our orientation); with
// `withAlpha`, SourceFace::alpha too.
SourceFaces facesFromLayout(const std::vector<RawImage>& images, EnvLayout layout, bool withAlpha = false);
// Faces of an OpenEXR cube map (ImfEnvmap CubeMap): pixel centres span the face edge to edge.
SourceFaces facesFromExrCube(const RawImage& image, bool withAlpha = false);
// Exact area-weighted resampling: each texel gets the solid-angle average of the source cells over it
// (colour, and alpha when the faces carry it, else A = 1).
CubeMap resampleFacesToCube(const SourceFaces& faces, int faceSize);
int sourceFaceSizeOf(const SourceFaces& faces);

// ---- lat-long (latlong_to_cube.cpp) ----
// resampleLatLongToCube with the environment rotated by `rotateRadians` about +Y (see IngestSettings);
// with `withAlpha`, A is resampled with the same weights as colour (else A = 1). `useSymmetry` false
// computes every texel's geometry itself (the reference the symmetric computation is tested against; the
// results differ by rounding only).
CubeMap resampleLatLongToCubeRotated(const ImageRGBA& latlong, int faceSize, LatLongPixels placement,
                                     double rotateRadians, bool withAlpha = false, bool useSymmetry = true);
// The same of RGBE pixels as stored (no alpha): the same values as of the decoded image, bit for bit.
CubeMap resampleLatLongToCubeRotated(const ImageRGBE& latlong, int faceSize, LatLongPixels placement,
                                     double rotateRadians, bool useSymmetry = true);
// A lat-long given to resampleLatLongBlocks in blocks of rows, each decoded when first asked for: block b
// holds rows [b * blockRows(), min(height(), (b + 1) * blockRows())).
class LatLongBlocks {
  public:
    virtual ~LatLongBlocks() = default;
    virtual int width() const = 0;
    virtual int height() const = 0;
    virtual int blockRows() const = 0;
    // Block b's pixels (R, G, B, A = 1), row-major, valid until release(b). Asked for once per block.
    virtual const glm::vec4* acquire(int block) = 0;
    virtual void release(int block) = 0;
};
// resampleLatLongToCubeRotated of a lat-long without alpha, the same values bit for bit, holding only the
// blocks that the texels being computed read: texels are computed in slabs by the last block they read
// (their rows from their extreme latitudes), each block acquired before the first slab that reads it and
// released after the last (the mirror images of the texels read the blocks at the bottom; docs/performance.md
// "Big HDRIs").
CubeMap resampleLatLongBlocks(LatLongBlocks& blocks, int faceSize, LatLongPixels placement,
                              double rotateRadians, bool useSymmetry = true);
// The blocks of an opened lat-long (read without alpha, from a source that reads rows in any order), each
// repaired, colour-converted (`convertColour`, convertColorRepaired in ingest; none for the identity) and its
// brightest luminance taken as ingestEnvironment does a whole image; released blocks' memory is reused.
// Blocks are `blockPixels` pixels or a little more (whole chunks, image_source.h). Throws NeedsWholeImage
// from acquire() when a block holds +Inf: its repair takes the largest finite value of the whole image.
struct NeedsWholeImage {};
// A streamed ingest's blocks: at least 64 rows and 2 Mi pixels, so that each read gives OpenEXR's threads
// many chunks to decode at once.
std::uint64_t defaultBlockPixels(int width);
class RepairedLatLongBlocks final : public LatLongBlocks {
  public:
    RepairedLatLongBlocks(OpenedImage& image, const glm::dvec3& luminanceWeights,
                          std::function<RepairCounts(ImageRGBA&)> convertColour, std::uint64_t blockPixels);
    int width() const override { return image_.raw.pixels.width; }
    int height() const override { return image_.raw.pixels.height; }
    int blockRows() const override { return blockRows_; }
    const glm::vec4* acquire(int block) override;
    void release(int block) override;
    // Decodes the blocks never acquired, so that repairs() and maxLuminance() are the whole image's.
    void decodeRest();
    RepairCounts repairs() const { return repairs_; }
    float maxLuminance() const { return maxLuminance_; }

  private:
    OpenedImage& image_;
    glm::dvec3 luminanceWeights_;
    std::function<RepairCounts(ImageRGBA&)> convertColour_;
    int blockRows_;
    std::vector<ImageRGBA> held_;               // per block; no pixels when not held
    std::vector<bool> decoded_;                 // per block
    std::vector<std::vector<glm::vec4>> spare_; // released blocks' pixels
    std::vector<float> strip_;                  // readRgbaRows' scratch
    RepairCounts repairs_;
    float maxLuminance_ = 0.0f;
};

// A resampled alpha as stored: clamped to [0, 1], and within 1e-6 of 0 or 1 taken as that (the exact-area
// average of cells that are all 1 may round to 0.99999994; it should not make a visible texel partial).
float resampledAlpha(double alpha);

// ---- rotation of a cube (rotate_cube.cpp) ----
// Rotates about +Y by supersampled bilinear lookups (approximate; used only for cube inputs).
CubeMap rotateCube(const CubeMap& cube, double rotateRadians);

} // namespace ibl::ingest
