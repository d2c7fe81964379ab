// A float RGBA image in memory: the currency between stages, backends and file writers.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/vec4.hpp>

namespace ibl {

struct ImageRGBA {
    int width = 0;
    int height = 0;
    std::vector<glm::vec4> pixels; // row-major, first row = first scanline

    ImageRGBA() = default;
    ImageRGBA(int w, int h) : width(w), height(h), pixels(std::size_t(w) * std::size_t(h)) {}
    glm::vec4& at(int x, int y) { return pixels[std::size_t(y) * std::size_t(width) + std::size_t(x)]; }
    const glm::vec4& at(int x, int y) const {
        return pixels[std::size_t(y) * std::size_t(width) + std::size_t(x)];
    }
};

} // namespace ibl
