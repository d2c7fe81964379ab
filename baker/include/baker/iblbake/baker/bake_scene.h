// Scene-driven bakes (docs/scenes.md "Scenes"): run a scene's plan through the stage cache and write the bake
// directory (products + manifest.json, written last). Re-entrant and free of global state: a batch runner
// may call bakeScene for many scenes, one after another or from several processes sharing a cache.
#pragma once

#include "iblbake/bake_state/bake_state.h"

namespace ibl {

// Never throws for a bad scene input, a failed stage or an unwritable output: the summary says what went
// wrong (ok = false, error) and the output directory keeps what it had (products are copied in only once
// every stage succeeded, the manifest last). Unless options.force, a bake that checkBakeUpToDate finds up to
// date is reported as such (reportUpToDateBake) without starting a backend or reading the cache.
BakeSummary bakeScene(const Scene& scene, const BakeOptions& options, ProgressSink& progress);

// bakeScene for a caller that has just made the check itself and found the bake stale (`checked`, e.g.
// iblbake batch): runs the stages without checking again, with the input hashes the check read.
BakeSummary bakeStaleScene(const Scene& scene, const BakeOptions& options, ProgressSink& progress,
                           const UpToDate& checked);

} // namespace ibl
