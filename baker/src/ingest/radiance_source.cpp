// Radiance RGBE (.hdr) files, read scanline by scanline (image_source.h). The format is small and its
// readers are not: stb_image (Debian libstb-dev) takes memory for the whole claimed size before it reads a
// pixel and decodes a truncated file as black without an error, and OpenImageIO is the start-up cost this
// reader avoids. Layout (Ward, "Real Pixels", Graphics Gems II, and Radiance's color.c): a text header
// "#?RADIANCE" (or "#?RGBE") with variable lines, a blank line, the resolution line "-Y <height> +X
// <width>", then one scanline after another: run-length encoded (2, 2, width high byte, width low byte, then
// each of R, G, B, E as runs: a count over 128 repeats the next byte count - 128 times, a count up to 128
// is followed by that many literal bytes) or flat RGBE pixels, where (1, 1, 1, n) repeats the previous
// pixel n << (8 * the number of such pixels just before it) times.
#include "image_source.h"
#include "rgbe.h"

#include "iblbake/core/error.h"
#include "iblbake/core/input_file.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace ibl::ingest {

namespace {

// A header longer than this is not a Radiance file (real ones hold a few hundred bytes).
constexpr std::size_t kMaxHeaderBytes = 64 * 1024;
// Run-length encoded scanlines have 8 to 32767 pixels (the length is stored in 15 bits).
constexpr int kMinEncodedWidth = 8, kMaxEncodedWidth = 0x7fff;

class BufferedFile {
  public:
    explicit BufferedFile(const std::filesystem::path& file) : in_(file) {}
    // The next byte, or -1 at the end of the file.
    int get() {
        const std::uint8_t* byte = take(1);
        return byte ? *byte : -1;
    }
    // The next n bytes (n at most the buffer's size), or nullptr when the file ends before them. The
    // pointer holds until the next call.
    const std::uint8_t* take(std::size_t n) {
        if (end_ - next_ < n && !refill(n)) return nullptr;
        const std::uint8_t* bytes = buffer_.data() + next_;
        next_ += n;
        return bytes;
    }

  private:
    // Keeps the unread bytes and reads more after them until n are there; false at the end of the file.
    bool refill(std::size_t n) {
        std::memmove(buffer_.data(), buffer_.data() + next_, end_ - next_);
        end_ -= next_;
        next_ = 0;
        while (end_ < n) {
            const std::size_t got =
                in_.read(reinterpret_cast<char*>(buffer_.data()) + end_, buffer_.size() - end_);
            if (got == 0) return false;
            end_ += got;
        }
        return true;
    }

    InputFile in_;
    std::array<std::uint8_t, 64 * 1024> buffer_{};
    std::size_t next_ = 0, end_ = 0;
};

class RadianceSource final : public ImageSource {
  public:
    RadianceSource(const std::filesystem::path& file, const std::string& name) : file_(file), name_(name) {
        readHeader();
    }

    void readRows(int y0, int y1, int begin, int end, float* data) override {
        if (y0 != stripY0_ || y1 != stripY1_) {
            strip_.resize(std::size_t(y1 - y0) * std::size_t(header_.width));
            readRgbeRows(y0, y1, strip_.data());
            stripY0_ = y0;
            stripY1_ = y1;
        }
        const std::size_t pixels = std::size_t(y1 - y0) * std::size_t(header_.width);
        const std::size_t channels = std::size_t(end - begin);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pixels, kPixelsPerTask),
                          [&](const tbb::blocked_range<std::size_t>& r) {
                              float* out = data + r.begin() * channels;
                              for (std::size_t i = r.begin(); i != r.end(); ++i) {
                                  const glm::vec4 rgb = decodeRgbe(strip_[i]);
                                  for (int c = begin; c < end; ++c)
                                      *out++ = rgb[c];
                              }
                          });
    }

    bool storesRgbe() const override { return true; }

    void readRgbeRows(int y0, int y1, RgbePixel* data) override {
        if (y0 != nextRow_) throw Error(name_ + ": cannot read pixels: rows asked for out of order");
        std::uint8_t* bytes = reinterpret_cast<std::uint8_t*>(data); // RgbePixel is 4 bytes, no padding
        for (int y = y0; y < y1; ++y)
            readScanline(bytes + std::size_t(y - y0) * std::size_t(header_.width) * 4, y);
        nextRow_ = y1;
    }

  private:
    [[noreturn]] void fail(const std::string& why) const { throw Error(name_ + ": " + why); }

    // One header line without its newline; fails at the end of the file or past kMaxHeaderBytes.
    std::string line() {
        std::string text;
        for (int c = file_.get(); c != '\n'; c = file_.get()) {
            if (c < 0) fail("not a Radiance file: the header has no end");
            if (++headerBytes_ > kMaxHeaderBytes) fail("not a Radiance file: the header is over 64 KiB");
            text.push_back(char(c));
        }
        ++headerBytes_;
        return text;
    }

    void readHeader() {
        const std::string magic = line();
        if (magic.rfind("#?", 0) != 0) fail("not a Radiance file (no #? on its first line)");
        for (std::string variable = line(); !variable.empty(); variable = line())
            if (variable.rfind("FORMAT=", 0) == 0 && variable != "FORMAT=32-bit_rle_rgbe")
                fail("Radiance " + variable.substr(7) + " is not supported (only 32-bit_rle_rgbe)");
        const std::string resolution = line();
        int height = 0, width = 0, consumed = 0;
        if (std::sscanf(resolution.c_str(), "-Y %d +X %d%n", &height, &width, &consumed) != 2 ||
            consumed != int(resolution.size()))
            fail("Radiance resolution line '" + printableForMessage(resolution) +
                 "' is not supported (only -Y <height> +X <width>)");
        if (width <= 0 || height <= 0)
            fail("image has no pixels (" + std::to_string(width) + "x" + std::to_string(height) + ")");
        header_.width = width;
        header_.height = height;
        header_.channels = {"R", "G", "B"};
        header_.colorSpace = "linear";
    }

    // The next n bytes of scanline y; fails when the file ends before them.
    const std::uint8_t* bytesOf(int y, std::size_t n) {
        const std::uint8_t* bytes = file_.take(n);
        if (!bytes)
            fail("cannot read pixels: the file ends in scanline " + std::to_string(y + 1) + " of " +
                 std::to_string(header_.height));
        return bytes;
    }

    void readScanline(std::uint8_t* rgbe, int y) {
        const int width = header_.width;
        std::array<std::uint8_t, 4> first{};
        std::memcpy(first.data(), bytesOf(y, 4), 4);
        const bool encoded = width >= kMinEncodedWidth && width <= kMaxEncodedWidth && first[0] == 2 &&
                             first[1] == 2 && (first[2] & 0x80) == 0;
        if (encoded) {
            if ((first[2] << 8 | first[3]) != width)
                fail("cannot read pixels: scanline " + std::to_string(y + 1) + " is encoded for " +
                     std::to_string(first[2] << 8 | first[3]) + " pixels, not " + std::to_string(width));
            // Each channel as runs; a literal run's bytes are taken from the buffer at once.
            for (int channel = 0; channel < 4; ++channel) {
                std::uint8_t* out = rgbe + channel;
                for (int x = 0; x < width;) {
                    int count = *bytesOf(y, 1);
                    const bool run = count > 128;
                    if (run) count -= 128;
                    if (count == 0 || count > width - x)
                        fail("cannot read pixels: a run in scanline " + std::to_string(y + 1) +
                             " overruns it");
                    if (run) {
                        const std::uint8_t repeated = *bytesOf(y, 1);
                        for (int k = 0; k < count; ++k)
                            out[4 * k] = repeated;
                    } else {
                        const std::uint8_t* literal = bytesOf(y, std::size_t(count));
                        for (int k = 0; k < count; ++k)
                            out[4 * k] = literal[k];
                    }
                    out += 4 * count;
                    x += count;
                }
            }
            return;
        }
        std::memcpy(rgbe, first.data(), 4);
        int shift = 0;
        for (int x = 1; x < width;) {
            std::uint8_t* pixel = rgbe + 4 * x;
            std::memcpy(pixel, bytesOf(y, 4), 4);
            if (pixel[0] == 1 && pixel[1] == 1 && pixel[2] == 1) {
                // Old-style run: the previous pixel again, the count in base 256 over consecutive runs.
                const std::uint64_t count = std::uint64_t(pixel[3]) << shift;
                if (count > std::uint64_t(width - x) || shift > 16)
                    fail("cannot read pixels: a run in scanline " + std::to_string(y + 1) + " overruns it");
                for (std::uint64_t k = 0; k < count; ++k, ++x)
                    std::memcpy(rgbe + 4 * x, rgbe + 4 * (x - 1), 4);
                shift += 8;
            } else {
                shift = 0;
                ++x;
            }
        }
    }

    BufferedFile file_;
    std::string name_;
    std::size_t headerBytes_ = 0;
    std::vector<RgbePixel> strip_;
    int stripY0_ = -1, stripY1_ = -1, nextRow_ = 0;
};

} // namespace

std::unique_ptr<ImageSource> openRadianceSource(const std::filesystem::path& file, const std::string& name) {
    return std::make_unique<RadianceSource>(file, name);
}

} // namespace ibl::ingest
