// Progress of a scene bake on the console (`iblbake bake`): a redrawn one-line bar with the stage and an ETA
// on a terminal, one line per stage otherwise, nothing when quiet, JSON event lines on stdout (docs/scenes.md
// "Progress"); at the end the summary line and the bake's report (BakeSummary::report). Beside the summary it
// prints (bakeSummaryJson), so that the front end and the engine report a bake the same way.
#pragma once

#include "iblbake/bake_state/bake_state.h"

#include <chrono>

namespace ibl {

enum class ProgressMode { Bar, Lines, Quiet, Json };

// Bar when stderr is a terminal, else Lines (unless quiet or json).
ProgressMode chooseProgressMode(bool quiet, bool json);

class ConsoleProgress : public ProgressSink {
  public:
    explicit ConsoleProgress(ProgressMode mode) : mode_(mode) {}
    void stageStart(const StageResult& stage, int index, int count) override;
    void stageEnd(const StageResult& stage, int index, int count) override;
    void done(const BakeSummary& summary) override;

  private:
    ProgressMode mode_;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
    bool barDrawn_ = false;
};

} // namespace ibl
