// Progress of a batch on the console (`iblbake batch`): the library's batch observer printing each stage and
// item as a line or a JSON event naming its item; lines from parallel items never interleave (one mutex).
// Lines mode prints one line per stage and per item on stderr, --quiet only errors, --json one JSON object
// per line on stdout (docs/batch.md "Batch").
#pragma once

#include "iblbake/bake_state/console_progress.h"
#include "iblbake/batch_run/batch_run.h"

#include <nlohmann/json.hpp>

#include <mutex>
#include <string>

namespace ibl {

class BatchProgress : public BatchObserver {
  public:
    explicit BatchProgress(ProgressMode mode)
        : mode_(mode == ProgressMode::Bar ? ProgressMode::Lines : mode) {}

    void batchStart(const BatchSummary& summary, const std::filesystem::path& summaryFile) override;
    void itemStart(const BatchItem& item) override;
    void stageStart(const BatchItem& item, const StageResult& stage, int index, int count) override;
    void stageEnd(const BatchItem& item, const StageResult& stage, int index, int count) override;
    void itemEnd(const BatchItemResult& result) override;
    void done(const BatchSummary& summary) override;

  private:
    // A JSON event line (--json only); `event` gets {"event": name}.
    void event(const std::string& name, nlohmann::json event);
    // A line on stderr (lines mode; failures also in quiet mode).
    void line(const std::string& text, bool isError = false);

    ProgressMode mode_;
    std::mutex mutex_;
};

} // namespace ibl
