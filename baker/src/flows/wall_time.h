// The flows' stage timing (product_flows.h StageTimed).
#pragma once

#include <chrono>

namespace ibl {

// Runs `work` and returns its wall time in milliseconds.
template <class Work>
double wallMilliseconds(Work&& work) {
    const auto start = std::chrono::steady_clock::now();
    work();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

} // namespace ibl
