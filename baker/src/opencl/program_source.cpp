// Assembles a program's source from the embedded kernel files: #include "x.h" is replaced by the
// file's text (each file once, like #pragma once) between #line markers, so a build log names the
// real file and line (kernels/dfg.h:42) although the device compiler never sees a file system.
#include "embedded_kernels.h"
#include "iblbake/core/error.h"
#include "iblbake/opencl/opencl_context.h"

#include <set>
#include <sstream>

namespace ibl::ocl {
namespace {

std::string_view findEmbedded(const std::string& name) {
    for (const EmbeddedFile& f : embeddedKernelFiles())
        if (f.name == name) return f.content;
    throw Error("kernels/" + name + ": not among the embedded kernel sources");
}

void appendFile(const std::string& name, std::set<std::string>& included, std::string& out) {
    if (!included.insert(name).second) return;
    std::istringstream in{std::string(findEmbedded(name))};
    out += "#line 1 \"kernels/" + name + "\"\n";
    std::string line;
    int lineNumber = 0;
    while (std::getline(in, line)) {
        ++lineNumber;
        std::size_t start = line.find_first_not_of(" \t");
        if (start != std::string::npos && line.compare(start, 8, "#include") == 0) {
            std::size_t open = line.find('"', start);
            std::size_t close = open == std::string::npos ? open : line.find('"', open + 1);
            if (close != std::string::npos) {
                appendFile(line.substr(open + 1, close - open - 1), included, out);
                out += "#line " + std::to_string(lineNumber + 1) + " \"kernels/" + name + "\"\n";
                continue;
            }
        }
        out += line;
        out += '\n';
    }
}

} // namespace

std::string assembleProgramSource(const std::string& mainFile) {
    std::set<std::string> included;
    std::string out;
    appendFile(mainFile, included, out);
    return out;
}

} // namespace ibl::ocl
