// Writes the KTX2 fuzz target's seed corpus into the directory given as the only argument: one good,
// small file per format and shape the writer produces (cube chains with several levels, a non-square 2D
// image, key/value data), so that mutations start from every valid structure.
#include <iblbake/ktx2/ktx2.h>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

namespace {

// A cube chain of face size `base` and every level down to 1x1, with distinct texel values.
ibl::CubeMapChain chainOf(int base) {
    ibl::CubeMapChain chain;
    for (int size = base; size >= 1; size /= 2) {
        ibl::CubeMap cube(size);
        for (int f = 0; f < 6; ++f)
            for (int y = 0; y < size; ++y)
                for (int x = 0; x < size; ++x)
                    cube.faces[f].at(x, y) =
                        glm::vec4(0.1f * float(f + 1), float(x) / float(size), float(y) * 3.0f, 1.0f);
        chain.levels.push_back(std::move(cube));
    }
    return chain;
}

} // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: ktx2_seeds DIRECTORY\n");
        return 2;
    }
    try {
        const std::filesystem::path dir = argv[1];
        std::filesystem::create_directories(dir);
        const ibl::Ktx2KeyValues keyValues = {{"iblbake.roughnessMapping", "frostbite"},
                                              {"iblbake.calibration.factor", "1.5"}};
        ibl::ImageRGBA lut(5, 3);
        for (std::size_t i = 0; i < lut.pixels.size(); ++i)
            lut.pixels[i] = glm::vec4(float(i) / 15.0f, 0.5f, 0.25f, 1.0f);
        const std::pair<ibl::Ktx2Format, const char*> formats[] = {{ibl::Ktx2Format::RGBA16F, "rgba16f"},
                                                                   {ibl::Ktx2Format::RGBA32F, "rgba32f"},
                                                                   {ibl::Ktx2Format::B10G11R11, "b10g11r11"},
                                                                   {ibl::Ktx2Format::E5B9G9R9, "e5b9g9r9"},
                                                                   {ibl::Ktx2Format::BC6H, "bc6h"}};
        for (const auto& [format, name] : formats) {
            ibl::writeKtx2Cube(dir / (std::string("cube4_") + name + ".ktx2"), chainOf(4), format, keyValues);
            ibl::writeKtx2Cube(dir / (std::string("cube1_") + name + ".ktx2"), chainOf(1), format, {});
            ibl::writeKtx2Image(dir / (std::string("image5x3_") + name + ".ktx2"), lut, format, {});
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "ktx2_seeds: %s\n", e.what());
        return 1;
    }
    return 0;
}
