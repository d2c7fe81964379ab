// The kernel headers in layers (issue 45): every file under kernels/ includes the kernel headers it uses at
// its top, before any code, and no chain of #include "..." leads back to a file it started from. With each
// header compiling alone (the KernelHeaderAlone.* tests of tests/CMakeLists.txt), that makes the headers a
// DAG a reader can take one at a time: a header cannot lean on names its includer happened to define first.
// Only quoted includes are the layers' edges: <...> ones are the C++ library's, inside C++-only branches.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

struct IncludeLine {
    std::string name; // the quoted file name
    int line;         // 1-based
};

struct FileIncludes {
    std::vector<IncludeLine> includes;
    int firstCodeLine = 0; // 0: no code
};

// The quoted includes of a source text and its first line of code: a line that is not blank, not a
// comment and not a preprocessor directive (include guards and language branches may come first).
FileIncludes scanIncludes(const std::string& text) {
    FileIncludes result;
    std::istringstream in(text);
    std::string line;
    bool inBlockComment = false;
    for (int number = 1; std::getline(in, line); ++number) {
        const std::size_t start = line.find_first_not_of(" \t");
        if (start == std::string::npos) continue;
        const std::string_view rest = std::string_view(line).substr(start);
        if (inBlockComment) {
            inBlockComment = rest.find("*/") == std::string_view::npos;
            continue;
        }
        if (rest.starts_with("//")) continue;
        if (rest.starts_with("/*")) {
            inBlockComment = rest.find("*/", 2) == std::string_view::npos;
            continue;
        }
        if (rest.starts_with("#")) {
            const std::size_t directive = rest.find_first_not_of(" \t", 1);
            if (directive != std::string_view::npos && rest.substr(directive).starts_with("include")) {
                const std::size_t open = rest.find('"'), close = rest.find('"', open + 1);
                if (open != std::string_view::npos && close != std::string_view::npos)
                    result.includes.push_back({std::string(rest.substr(open + 1, close - open - 1)), number});
            }
            continue;
        }
        if (result.firstCodeLine == 0) result.firstCodeLine = number;
    }
    return result;
}

// The includes of a file that come after its first line of code, as "name:line".
std::vector<std::string> includesAfterCode(const FileIncludes& file) {
    std::vector<std::string> late;
    for (const IncludeLine& include : file.includes)
        if (file.firstCodeLine != 0 && include.line > file.firstCodeLine)
            late.push_back(include.name + ":" + std::to_string(include.line));
    return late;
}

using IncludeGraph = std::map<std::string, std::vector<std::string>>;

// A cycle of the graph as the files along it, its first file repeated at the end; empty for a DAG.
std::vector<std::string> includeCycle(const IncludeGraph& graph) {
    enum class State { Unvisited, OnPath, Done };
    std::map<std::string, State> state;
    std::vector<std::string> path, cycle;
    auto visit = [&](auto& self, const std::string& file) -> bool {
        state[file] = State::OnPath;
        path.push_back(file);
        const auto edges = graph.find(file);
        if (edges != graph.end())
            for (const std::string& next : edges->second) {
                if (state[next] == State::OnPath) {
                    cycle.assign(std::find(path.begin(), path.end(), next), path.end());
                    cycle.push_back(next);
                    return true;
                }
                if (state[next] == State::Unvisited && self(self, next)) return true;
            }
        path.pop_back();
        state[file] = State::Done;
        return false;
    };
    for (const auto& [file, edges] : graph)
        if (state[file] == State::Unvisited && visit(visit, file)) return cycle;
    return {};
}

std::string joined(const std::vector<std::string>& names, const char* separator) {
    std::string out;
    for (const std::string& name : names)
        out += (out.empty() ? "" : separator) + name;
    return out;
}

// Every .h and .cl file under kernels/ with its text.
std::map<std::string, std::string> kernelFiles() {
    std::map<std::string, std::string> files;
    for (const fs::directory_entry& entry :
         fs::directory_iterator(fs::path(IBLBAKE_SOURCE_DIR) / "kernels")) {
        const std::string extension = entry.path().extension().string();
        if (extension != ".h" && extension != ".cl") continue;
        std::ifstream in(entry.path());
        files[entry.path().filename().string()] = std::string(std::istreambuf_iterator<char>(in), {});
    }
    return files;
}

TEST(KernelHeaders, ScanFindsIncludesAfterCode) {
    const FileIncludes file = scanIncludes("// lead\n#ifndef A_H\n#define A_H\n\n#include \"b.h\"\n/* block\n"
                                           "still */\nIBL_BEGIN_NAMESPACE\n#include \"c.h\"\n#endif\n");
    ASSERT_EQ(file.includes.size(), 2u);
    EXPECT_EQ(file.includes[0].name, "b.h");
    EXPECT_EQ(file.firstCodeLine, 8);
    EXPECT_EQ(includesAfterCode(file), std::vector<std::string>{"c.h:9"});
}

TEST(KernelHeaders, CycleIsFoundAndADagHasNone) {
    EXPECT_EQ(includeCycle({{"a.h", {"b.h"}}, {"b.h", {"c.h"}}, {"c.h", {"a.h"}}}),
              (std::vector<std::string>{"a.h", "b.h", "c.h", "a.h"}));
    EXPECT_EQ(includeCycle({{"a.h", {"b.h"}}, {"b.h", {"c.h"}}, {"d.h", {"b.h"}}, {"c.h", {}}}),
              std::vector<std::string>{});
}

TEST(KernelHeaders, IncludeOnlyAtTheirTop) {
    const std::map<std::string, std::string> files = kernelFiles();
    ASSERT_GT(files.size(), 20u);
    for (const auto& [name, text] : files)
        EXPECT_EQ(joined(includesAfterCode(scanIncludes(text)), ", "), "")
            << "kernels/" << name << " includes these after its first line of code";
}

TEST(KernelHeaders, IncludeExistingFilesWithoutCycles) {
    const std::map<std::string, std::string> files = kernelFiles();
    IncludeGraph graph;
    for (const auto& [name, text] : files)
        for (const IncludeLine& include : scanIncludes(text).includes) {
            EXPECT_TRUE(files.contains(include.name))
                << "kernels/" << name << ":" << include.line << " includes " << include.name
                << ", which is not under kernels/ (the OpenCL program assembly would not find it)";
            graph[name].push_back(include.name);
        }
    EXPECT_EQ(joined(includeCycle(graph), " -> "), "");
}

} // namespace
