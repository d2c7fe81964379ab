// The runtime's multi-tap specular lookup (kernels/specular_taps.h): the checked-in table is what the fitting
// program (tools/specular_taps) computes, it beats the split sum's single read in the program's own measure,
// and the runtime reads it as the table says.
#include <specular_taps.h>
#include <specular_taps_fit.h>

#include <gtest/gtest.h>

namespace {

using namespace ibl;

// The table's taps of cell (i, j) as the fitting program states them.
taps::CellFit tableCell(int i, int j) {
    taps::CellFit cell;
    cell.tapCount = int(IBL_SPECULAR_TAP_COUNT);
    const std::size_t first = std::size_t(j * taps::kGridSize + i) * 3u * IBL_SPECULAR_TAP_COUNT;
    for (int k = 0; k < cell.tapCount; ++k) {
        const float* t = &kSpecularTapTable[first + 3u * std::size_t(k)];
        cell.taps[std::size_t(k)] = {t[0], double(t[1]) * taps::cellRoughness(j), t[2]};
    }
    cell.residual = kSpecularTapResidual[std::size_t(j * taps::kGridSize + i)];
    return cell;
}

struct Cell {
    int i, j;
};
// Grazing, middle and near-normal views at r = 0.2, 0.53 and 0.87 (a second each).
constexpr Cell kCells[] = {{2, 3}, {8, 8}, {13, 13}};

TEST(SpecularTaps, TableIsTheProgramsFit) {
    ASSERT_EQ(taps::kGridSize, int(IBL_SPECULAR_TAP_GRID));
    for (Cell c : kCells) {
        const double NoV = taps::cellNoV(c.i), r = taps::cellRoughness(c.j);
        const std::vector<double> lobe = taps::lobeCoefficients(NoV, r);
        const taps::CellFit table = tableCell(c.i, c.j);
        // The table's taps have the residual the program recorded (6-digit rounding of the table only)...
        const double residual = taps::tapsResidual(lobe, NoV, table.taps.data(), table.tapCount);
        EXPECT_NEAR(residual, table.residual, 1e-3 + 0.01 * table.residual) << "NoV " << NoV << " r " << r;
        // ... and the program, started there, finds nothing better: the table is its minimum.
        const taps::CellFit refit = taps::fitCell(lobe, NoV, r, table.tapCount, &table);
        EXPECT_GT(refit.residual, 0.98 * residual) << "NoV " << NoV << " r " << r;
        // The taps stand for the view's lobe better than the split sum's single read does.
        const taps::CellFit split = taps::splitSumCell(NoV, r);
        EXPECT_LT(residual, taps::tapsResidual(lobe, NoV, split.taps.data(), 1))
            << "NoV " << NoV << " r " << r;
    }
}

TEST(SpecularTaps, RuntimeReadsTheTable) {
    // At a cell's (NoV, r) the lookup returns the cell; between cells the weights still sum to 1.
    for (Cell c : kCells) {
        const taps::CellFit table = tableCell(c.i, c.j);
        const float NoV = float(c.i) / float(taps::kGridSize - 1), r = float(taps::cellRoughness(c.j));
        for (uint k = 0; k < IBL_SPECULAR_TAP_COUNT; ++k) {
            const SpecularTap tap = specularTap(NoV, r, k);
            EXPECT_NEAR(tap.lerpFactor, table.taps[k].lerpFactor, 1e-5);
            EXPECT_NEAR(tap.perceptualRoughness, std::min(1.0, table.taps[k].roughness), 1e-5);
            EXPECT_NEAR(tap.weight, table.taps[k].weight, 1e-5);
        }
    }
    for (float NoV : {0.0f, 0.31f, 0.77f, 1.0f})
        for (float r : {0.0f, 0.05f, 0.42f, 0.99f, 1.0f}) {
            float sum = 0.0f;
            for (uint k = 0; k < IBL_SPECULAR_TAP_COUNT; ++k)
                sum += specularTap(NoV, r, k).weight;
            EXPECT_NEAR(sum, 1.0f, 1e-5f) << NoV << " " << r;
        }
    // A mirror reads R at r = 0 with every tap.
    for (uint k = 0; k < IBL_SPECULAR_TAP_COUNT; ++k) {
        EXPECT_EQ(specularTap(0.6f, 0.0f, k).lerpFactor, 1.0f);
        EXPECT_EQ(specularTap(0.6f, 0.0f, k).perceptualRoughness, 0.0f);
    }
}

} // namespace
