// Progress of `iblbake bake`: a redrawn one-line bar with the stage and an ETA on a terminal, one line per
// stage otherwise, nothing with --quiet, JSON event lines on stdout with --json. A stage that waits on a
// compile or the preview's reference says so, with its estimate, on the bar, on a line of its own, or as a
// "stage-waiting" event.
#pragma once

#include <iblbake/bake_state/bake_state.h>

#include <chrono>

namespace ibl::cli {

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

} // namespace ibl::cli
