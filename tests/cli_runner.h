// Runs the iblbake executable as a user would and captures exit code, stdout and stderr.
#pragma once

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace ibl::test {

// The sample HDRI the README's commands bake (data/README.md).
inline const std::string kSampleHdri = std::string(IBLBAKE_SOURCE_DIR) + "/data/rooitou_park_1k.hdr";

struct CliRun {
    int exitCode = -1;
    std::string out;
    std::string err;
};

// `program` is a shell command prefix, e.g. "env IBLBAKE_ENGINE=/x " IBLBAKE_CLI.
inline CliRun runProgram(const std::string& program, const std::string& args) {
    namespace fs = std::filesystem;
    fs::path errFile = fs::temp_directory_path() / ("iblbake_cli_err_" + std::to_string(::getpid()));
    std::string cmd = program + " " + args + " 2>" + errFile.string();
    CliRun r;
    FILE* pipe = ::popen(cmd.c_str(), "r");
    std::array<char, 4096> buf;
    while (std::size_t n = std::fread(buf.data(), 1, buf.size(), pipe))
        r.out.append(buf.data(), n);
    int status = ::pclose(pipe);
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::ifstream in(errFile);
    r.err.assign(std::istreambuf_iterator<char>(in), {});
    fs::remove(errFile);
    return r;
}

inline CliRun runCli(const std::string& args) {
    return runProgram(IBLBAKE_CLI, args);
}

// The engine behind the front end (cli/front_end.cpp), run directly.
inline std::string enginePath() {
    return (std::filesystem::path(IBLBAKE_CLI).parent_path() / "iblbake-engine").string();
}

inline int lineCount(const std::string& s) {
    return int(std::count(s.begin(), s.end(), '\n'));
}

// How many times `what` occurs in `text`, not overlapping.
inline std::size_t occurrences(const std::string& text, const std::string& what) {
    std::size_t count = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size()))
        ++count;
    return count;
}

// A fresh, empty directory under the system temp directory.
inline std::filesystem::path freshTempDir(const std::string& name) {
    namespace fs = std::filesystem;
    fs::path dir = fs::temp_directory_path() / ("iblbake_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

inline std::size_t entryCount(const std::filesystem::path& dir) {
    return std::size_t(
        std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()));
}

} // namespace ibl::test
