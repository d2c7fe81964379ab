// iblbake-fit-specular-taps OUTPUT: fits the runtime's multi-tap specular lookup (specular_taps_fit.h) and
// writes the header kernels/specular_taps_table.h to OUTPUT; prints each roughness row's mean residual
// against the split sum's.
#include "specular_taps_fit.h"

#include <cstdio>
#include <fstream>

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: iblbake-fit-specular-taps OUTPUT.h\n");
        return 2;
    }
    using namespace ibl::taps;
    constexpr int kTapCount = 2;
    const std::vector<CellFit> table = fitTable(kTapCount);
    for (int j = 1; j < kGridSize; ++j) {
        double fitted = 0.0, split = 0.0;
        for (int i = 0; i < kGridSize; ++i) {
            const std::vector<double> lobe = lobeCoefficients(cellNoV(i), cellRoughness(j));
            fitted += table[std::size_t(j * kGridSize + i)].residual / kGridSize;
            split +=
                tapsResidual(lobe, cellNoV(i), splitSumCell(cellNoV(i), cellRoughness(j)).taps.data(), 1) /
                kGridSize;
        }
        std::printf("r %.3f: mean residual %d taps %.4f, split sum %.4f\n", cellRoughness(j), kTapCount,
                    fitted, split);
    }
    std::ofstream out(argv[1], std::ios::binary);
    out << tableHeaderText(table, kTapCount);
    if (!out) {
        std::fprintf(stderr, "%s: cannot write\n", argv[1]);
        return 1;
    }
    return 0;
}
