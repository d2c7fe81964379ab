// Progress of a scene bake on the console (`iblbake bake`): a redrawn one-line bar with the stage and an ETA
// on a terminal, one line per stage otherwise, nothing when quiet, JSON event lines on stdout (docs/scenes.md
// "Progress"); at the end the summary line and the bake's report (BakeSummary::report). Beside the summary it
// prints (bakeSummaryJson), so that the front end and the engine report a bake the same way. A stage that
// waits on a compile or the preview's reference says so, with its estimate, on the bar, on a line of its own,
// or as a "stage-waiting" event.
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
    void stageWaiting(const StageResult& stage, const std::string& what, const std::string& detail,
                      double secondsLeft) override;
    void done(const BakeSummary& summary) override;

  private:
    ProgressMode mode_;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
    bool barDrawn_ = false;
    std::string barLine_; // the bar as its stage's start drew it
};

} // namespace ibl
