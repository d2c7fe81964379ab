// W(alpha): the integral of GGX D(h) NoL over the light directions l with N = V, by which ld.h normalizes a
// bright texel's exact contribution (LdParams::invLobeIntegral).
#pragma once

namespace ibl {

double lobeIntegral(double alpha);

} // namespace ibl
