// Progress of `iblbake batch`: the scene bake's ProgressSink per item, each line or JSON event naming its
// item; lines from parallel items never interleave (one mutex). Lines mode prints one line per stage and per
// item on stderr, --quiet only errors, --json one JSON object per line on stdout (README "Batch").
#pragma once

#include "scene_progress.h"

#include <iblbake/bake_scene.h>

#include <nlohmann/json.hpp>

#include <mutex>
#include <string>

namespace ibl::cli {

class BatchProgress {
  public:
    explicit BatchProgress(ProgressMode mode)
        : mode_(mode == ProgressMode::Bar ? ProgressMode::Lines : mode) {}

    // A JSON event line (--json only); `event` gets {"event": name}.
    void event(const std::string& name, nlohmann::json event);
    // A line on stderr (lines mode; failures also in quiet mode).
    void line(const std::string& text, bool isError = false);
    ProgressMode mode() const { return mode_; }

  private:
    ProgressMode mode_;
    std::mutex mutex_;
};

// The sink one item's bake reports to.
class ItemProgress : public ProgressSink {
  public:
    ItemProgress(BatchProgress& batch, std::string item) : batch_(batch), item_(std::move(item)) {}
    void stageStart(const StageResult& stage, int index, int count) override;
    void stageEnd(const StageResult& stage, int index, int count) override;

  private:
    BatchProgress& batch_;
    std::string item_;
};

} // namespace ibl::cli
