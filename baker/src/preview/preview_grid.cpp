// The material preview's labelled grid (preview_grid.h). Text is drawn by OpenImageIO's render_text
// (FreeType, through the OpenImageIO module) in DejaVu Sans from Debian's fonts-dejavu-core.
#include "preview_grid.h"

#include "../io/oiio_module.h"

#include "iblbake/baker/preview.h"
#include "iblbake/core/error.h"

#include <algorithm>

#include <cmath>
#include <cstdio>

namespace ibl {

namespace {

using oiio_module::TextAlign;

constexpr const char* kFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
constexpr float kBackground = 0.14f; // the grid's dark grey; the balls' cells are black
constexpr float kText[3] = {0.92f, 0.92f, 0.92f};
constexpr float kErrorScaleMax = 0.2f; // previewErrorColor saturates at 20%

std::string percent(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f%%", 100.0 * value);
    return text;
}

class Canvas {
  public:
    Canvas(const std::filesystem::path& png, int width, int height)
        : png_(png), width_(width), height_(height),
          rgb_(std::size_t(width) * std::size_t(height) * 3, kBackground) {}
    void set(int x, int y, const glm::vec3& display) {
        float* p = &rgb_[(std::size_t(y) * std::size_t(width_) + std::size_t(x)) * 3];
        p[0] = display.x;
        p[1] = display.y;
        p[2] = display.z;
    }
    void fill(int x, int y, int width, int height, const glm::vec3& display) {
        for (int py = std::max(y, 0); py < std::min(y + height, height_); ++py)
            for (int px = std::max(x, 0); px < std::min(x + width, width_); ++px)
                set(px, py, display);
    }
    void text(int x, int y, const std::string& text, int fontSize, TextAlign align = TextAlign::Left) {
        std::string why;
        if (!oiio_module::api(png_.string() + ": the labels")
                 .drawText(rgb_.data(), width_, height_, x, y, text, fontSize, kFont, kText, align, why))
            throw Error(png_.string() + ": cannot draw the labels (" + why + "): they need DejaVu Sans, " +
                        kFont + " (Debian fonts-dejavu-core)");
    }
    void write() const {
        std::vector<unsigned char> rgb(rgb_.size());
        for (std::size_t i = 0; i < rgb_.size(); ++i)
            rgb[i] = (unsigned char)std::lround(255.0f * std::clamp(rgb_[i], 0.0f, 1.0f));
        writeSrgb8Png(png_, width_, height_, rgb);
    }

  private:
    std::filesystem::path png_;
    int width_, height_;
    std::vector<float> rgb_; // display-encoded RGB, rows top to bottom
};

} // namespace

std::vector<ShadingPoint>
previewBallPoints(int size, int columns, int rows, std::vector<int>& owner,
                  const std::function<void(ShadingPoint&, int row, int column)>& material) {
    const int width = columns * size, height = rows * size;
    owner.assign(std::size_t(width) * height, -1);
    std::vector<ShadingPoint> points;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            float u = (float(x % size) + 0.5f) / float(size) * 2.0f - 1.0f;
            float v = 1.0f - (float(y % size) + 0.5f) / float(size) * 2.0f;
            float rr = (u * u + v * v) / 0.81f; // radius 0.9 of the cell
            if (rr >= 1.0f) continue;
            ShadingPoint p{};
            p.normal = glm::vec3(u / 0.9f, v / 0.9f, std::sqrt(1.0f - rr));
            p.view = glm::vec3(0.0f, 0.0f, 1.0f);
            p.ao = 1.0f;
            material(p, y / size, x / size);
            owner[std::size_t(y) * width + x] = int(points.size());
            points.push_back(p);
        }
    return points;
}

int PreviewLayout::cellX(int column) const {
    return margin + labelWidth + column * columnWidth + (columnWidth - sphereSize) / 2;
}

int PreviewLayout::cellY(int row) const {
    // Rows come in groups (runtime [, reference, error] of one material); an error row is followed by two
    // lines of per-column values (the error, the reference's own estimated error), and the groups by a gap.
    const int perGroup = rowCount / groupCount, group = row / perGroup;
    const int valueLines = perGroup == 3 ? group : 0;
    return headerHeight + row * sphereSize + group * groupGap + valueLines * 3 * fontSize;
}

PreviewLayout previewLayout(int sphereSize, bool withReference, int groupCount, int columnCount) {
    PreviewLayout l;
    l.sphereSize = sphereSize;
    l.groupCount = groupCount;
    l.columnCount = columnCount;
    l.fontSize = std::max(12, sphereSize / 7);
    l.margin = l.fontSize;
    l.columnWidth = std::max(sphereSize, 4 * l.fontSize); // "10.0%" fits
    l.labelWidth = 13 * l.fontSize;                       // "reference dielectric" in DejaVu Sans is ~11 em
    l.headerHeight = 4 * l.fontSize;
    l.rowCount = (withReference ? 3 : 1) * groupCount;
    l.groupGap = l.fontSize;
    l.legendHeight = withReference ? 5 * l.fontSize : 0;
    l.width = 2 * l.margin + l.labelWidth + columnCount * l.columnWidth;
    const int valueLine = withReference ? 3 * l.fontSize : 0;
    l.height = l.cellY(l.rowCount - 1) + sphereSize + valueLine + l.legendHeight + l.margin;
    return l;
}

std::vector<std::string> previewRowNames(bool withReference, const std::vector<std::string>& groups) {
    std::vector<std::string> names;
    for (const std::string& group : groups)
        for (const char* kind : {"runtime ", "reference ", "error "}) {
            names.push_back(kind + group);
            if (!withReference) break;
        }
    return names;
}

void writePreviewGrid(const std::filesystem::path& png, const PreviewLayout& l, const ImageRGBA& panels,
                      const std::vector<glm::vec3>& errorColor, const std::vector<int>& owner, float scale,
                      const PreviewGridLabels& labels) {
    const bool withReference = l.rowCount == 3 * l.groupCount;
    const int size = l.sphereSize, panelWidth = l.columnCount * size;
    Canvas canvas(png, l.width, l.height);
    const int fs = l.fontSize;

    // Header: the caption, then each column's roughness.
    canvas.text(l.cellX(0), fs, labels.caption, fs);
    for (int c = 0; c < l.columnCount; ++c) {
        char value[16];
        std::snprintf(value, sizeof value, "%.1f", labels.roughness[std::size_t(c)]);
        canvas.text(l.cellX(c) + size / 2, l.headerHeight - fs, value, fs, TextAlign::Centre);
    }

    const std::vector<std::string> names = previewRowNames(withReference, labels.groups);
    for (int row = 0; row < l.rowCount; ++row) {
        const int perGroup = l.rowCount / l.groupCount, group = row / perGroup,
                  kind = row % perGroup; // 0 runtime
        const int top = l.cellY(row);
        canvas.text(l.margin, top + size / 2, names[std::size_t(row)], fs);
        for (int c = 0; c < l.columnCount; ++c)
            canvas.fill(l.cellX(c), top, size, size, glm::vec3(0.0f));
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < panelWidth; ++x) {
                const int panelY = group * size + y;
                const int k = owner[std::size_t(panelY) * panelWidth + x];
                if (k < 0) continue;
                glm::vec3 display;
                if (kind == 2) {
                    display = errorColor[std::size_t(k)];
                } else {
                    const glm::vec4& linear = panels.at(kind * panelWidth + x, panelY);
                    for (int ch = 0; ch < 3; ++ch)
                        display[ch] = float(tonemapToSrgb8(linear[ch], scale)) / 255.0f;
                }
                canvas.set(l.cellX(x / size) + x % size, top + y, display);
            }
        if (kind == 2) { // the row's per-column error
            const std::vector<double>& error = labels.error[std::size_t(group)];
            const std::vector<double>& own = labels.referenceError[std::size_t(group)];
            canvas.text(l.margin, top + size + fs, "mean error", fs);
            canvas.text(l.margin, top + size + 2 * fs, "reference's own", fs);
            for (int c = 0; c < l.columnCount; ++c) {
                canvas.text(l.cellX(c) + size / 2, top + size + fs, percent(error[std::size_t(c)]), fs,
                            TextAlign::Centre);
                canvas.text(l.cellX(c) + size / 2, top + size + 2 * fs, percent(own[std::size_t(c)]), fs,
                            TextAlign::Centre);
            }
        }
    }

    if (withReference) { // the error colour scale: a bar from 0 to 20% and more, with its values
        const int top = l.height - l.margin - l.legendHeight + fs;
        const int barWidth = l.columnCount * l.columnWidth / 2, barHeight = fs;
        canvas.text(l.margin, top + barHeight / 2, "error scale", fs);
        for (int x = 0; x < barWidth; ++x)
            canvas.fill(l.cellX(0) + x, top, 1, barHeight,
                        previewErrorColor(kErrorScaleMax * float(x) / float(barWidth - 1)));
        const char* ticks[5] = {"0", "5%", "10%", "15%", ">= 20%"};
        for (int t = 0; t < 5; ++t)
            canvas.text(l.cellX(0) + t * (barWidth - 1) / 4, top + barHeight + fs, ticks[t], fs,
                        t == 0   ? TextAlign::Left
                        : t == 4 ? TextAlign::Right
                                 : TextAlign::Centre);
        canvas.text(l.cellX(0) + barWidth + fs, top + barHeight / 2,
                    "|runtime - reference| / reference, luminance", fs);
    }
    canvas.write();
}

} // namespace ibl
