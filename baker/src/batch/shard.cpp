// Shards of a batch (batch.h): from --shard K/N or a scheduler's job-array variables.
#include "iblbake/batch/batch.h"

#include "iblbake/core/error.h"

#include <charconv>

namespace ibl {

namespace {

std::optional<long> wholeNumber(std::string_view text) {
    long value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || text.empty()) return std::nullopt;
    return value;
}

long variable(const std::function<const char*(const char*)>& env, const char* name) {
    const char* text = env(name);
    const std::optional<long> value = text ? wholeNumber(text) : std::nullopt;
    if (!value) throw Error(std::string(name) + ": '" + (text ? text : "") + "' is not a whole number");
    return *value;
}

Shard checked(long index, long count, const std::string& source, const std::string& what) {
    if (count < 1 || count > 1000000)
        throw Error(what + ": the shard count " + std::to_string(count) + " is not from 1 to 1000000");
    if (index < 0 || index >= count)
        throw Error(what + ": shard " + std::to_string(index) + " is not from 0 to " +
                    std::to_string(count - 1));
    return Shard{int(index), int(count), source};
}

} // namespace

bool inShard(const BatchItem& item, const Shard& shard) {
    return int(item.index % std::size_t(shard.count)) == shard.index;
}

Shard parseShard(const std::string& text) {
    const std::size_t slash = text.find('/');
    const std::optional<long> k = wholeNumber(std::string_view(text).substr(0, slash));
    const std::optional<long> n =
        slash == std::string::npos ? std::nullopt : wholeNumber(std::string_view(text).substr(slash + 1));
    if (!k || !n || *n < 1 || *k < 1 || *k > *n)
        throw Error("--shard: '" + text + "' is not K/N with 1 <= K <= N");
    return checked(*k - 1, *n, "--shard", "--shard");
}

std::optional<Shard> shardFromEnvironment(const std::function<const char*(const char*)>& env,
                                          std::optional<int> countOverride) {
    if (env("SLURM_ARRAY_TASK_ID")) {
        const long id = variable(env, "SLURM_ARRAY_TASK_ID");
        const long min = env("SLURM_ARRAY_TASK_MIN") ? variable(env, "SLURM_ARRAY_TASK_MIN") : 0;
        long count = 0;
        if (env("SLURM_ARRAY_TASK_COUNT"))
            count = variable(env, "SLURM_ARRAY_TASK_COUNT");
        else if (env("SLURM_ARRAY_TASK_MAX"))
            count = variable(env, "SLURM_ARRAY_TASK_MAX") - min + 1;
        else
            throw Error("SLURM_ARRAY_TASK_ID: set without SLURM_ARRAY_TASK_COUNT or SLURM_ARRAY_TASK_MAX");
        return checked(id - min, count, "SLURM_ARRAY_TASK_ID", "SLURM_ARRAY_TASK_ID");
    }
    if (env("JOB_COMPLETION_INDEX")) {
        const long index = variable(env, "JOB_COMPLETION_INDEX");
        long count = 0;
        if (countOverride)
            count = *countOverride;
        else if (env("IBLBAKE_SHARD_COUNT"))
            count = variable(env, "IBLBAKE_SHARD_COUNT");
        else
            throw Error("JOB_COMPLETION_INDEX: set without --shard-count or IBLBAKE_SHARD_COUNT");
        return checked(index, count, "JOB_COMPLETION_INDEX", "JOB_COMPLETION_INDEX");
    }
    return std::nullopt;
}

} // namespace ibl
