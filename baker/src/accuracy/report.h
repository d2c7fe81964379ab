// The outputs of `iblbake accuracy`: report.json (every measurement), report.md (the README's "What
// accuracy costs in time" table) and report.html (one inline SVG plot of error against time per stage).
#pragma once

#include "model.h"

#include <string>

namespace ibl::cli {

std::string accuracyJson(const AccuracyRun& run);
std::string accuracyMarkdown(const AccuracyRun& run);
std::string accuracyHtml(const AccuracyRun& run);

} // namespace ibl::cli
