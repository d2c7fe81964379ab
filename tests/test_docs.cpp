// The documentation says what the code does (issue 45): every CLI usage the README and docs/*.md show names a
// subcommand and flags the built iblbake accepts (asked through `--help`), every key of docs/scenes.md's
// schema table is one parseScene knows, every relative link and every `docs/X.md "Section"` citation in the
// sources points at an existing file and heading, and the README stays a five-minute read (at most 300
// lines). Each failure names the doc file and line.
#include "cli_runner.h"

#include <iblbake/core/error.h>
#include <iblbake/scene/scene.h>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

namespace fs = std::filesystem;
using nlohmann::json;
using namespace ibl::test;

namespace {

const fs::path kSource = IBLBAKE_SOURCE_DIR;

// One line of a Markdown file, split into what is code (a fenced block's line, or inline `spans`) and what is
// not.
struct DocLine {
    std::string file; // relative to the source root, for messages
    int number = 0;
    std::string text;
    bool inFence = false;
    std::vector<std::string> codeSpans; // the whole line in a fence, else the inline spans
    std::string heading;                // the nearest heading above (its text)
};

std::vector<fs::path> docFiles() {
    std::vector<fs::path> files = {kSource / "README.md"};
    std::vector<fs::path> docs;
    for (const auto& entry : fs::directory_iterator(kSource / "docs"))
        if (entry.path().extension() == ".md") docs.push_back(entry.path());
    std::sort(docs.begin(), docs.end());
    files.insert(files.end(), docs.begin(), docs.end());
    return files;
}

std::vector<std::string> inlineCodeSpans(const std::string& line) {
    std::vector<std::string> spans;
    for (std::size_t open = line.find('`'); open != std::string::npos;) {
        const std::size_t close = line.find('`', open + 1);
        if (close == std::string::npos) break;
        spans.push_back(line.substr(open + 1, close - open - 1));
        open = line.find('`', close + 1);
    }
    return spans;
}

std::vector<DocLine> readDoc(const fs::path& file) {
    std::ifstream in(file);
    std::vector<DocLine> lines;
    bool inFence = false;
    std::string heading;
    int number = 0;
    for (std::string text; std::getline(in, text);) {
        DocLine line{fs::relative(file, kSource).string(), ++number, text, inFence, {}, heading};
        if (text.rfind("```", 0) == 0) {
            inFence = !inFence;
            continue;
        }
        if (inFence) {
            line.codeSpans = {text};
        } else {
            line.codeSpans = inlineCodeSpans(text);
            if (text.rfind('#', 0) == 0) heading = text.substr(text.find_first_not_of("# "));
        }
        line.heading = heading;
        lines.push_back(line);
    }
    return lines;
}

std::string where(const DocLine& line) {
    return line.file + ":" + std::to_string(line.number);
}

// ---------------------------------------------------------------------------------------------------------
// CLI usages

const std::regex kFlag(R"(--[a-z][a-z0-9-]*)");

std::vector<std::string> flagsIn(const std::string& text) {
    std::vector<std::string> flags;
    for (auto it = std::sregex_iterator(text.begin(), text.end(), kFlag); it != std::sregex_iterator(); ++it)
        flags.push_back(it->str());
    return flags;
}

// `iblbake SUB ...` in a code span: the subcommand and the flags up to the end of that command (&&, |, ;).
struct Usage {
    std::string subcommand;
    std::vector<std::string> flags;
};

std::vector<Usage> usagesIn(const std::string& code) {
    static const std::regex command(R"((?:^|[\s/(])iblbake\s+([a-z][a-z0-9-]*))");
    std::vector<Usage> usages;
    for (auto it = std::sregex_iterator(code.begin(), code.end(), command); it != std::sregex_iterator();
         ++it) {
        const std::size_t from = std::size_t(it->position(0) + it->length(0));
        std::size_t to = code.size();
        for (const char* end : {"&&", "|", ";", " iblbake "})
            to = std::min(to, code.find(end, from));
        usages.push_back({(*it)[1].str(), flagsIn(code.substr(from, to - from))});
    }
    return usages;
}

// What `iblbake [SUB] --help` prints, asked once per subcommand.
const std::string& helpText(const std::string& subcommand) {
    static std::map<std::string, std::string> cache;
    auto [it, inserted] = cache.try_emplace(subcommand);
    if (inserted) {
        const CliRun run = runCli((subcommand.empty() ? "" : subcommand + " ") + "--help");
        it->second = run.exitCode == 0 ? run.out : "";
    }
    return it->second;
}

// The flag as a whole word of the help text (`--size` must not match `--size-x`).
bool helpHasFlag(const std::string& help, const std::string& flag) {
    for (std::size_t at = help.find(flag); at != std::string::npos; at = help.find(flag, at + 1)) {
        const std::size_t end = at + flag.size();
        const bool wordEnds = end == help.size() || !(std::isalnum(static_cast<unsigned char>(help[end])) ||
                                                      help[end] == '-' || help[end] == '_');
        if (wordEnds) return true;
    }
    return false;
}

// The subcommands `iblbake --help` lists: the first word of each indented line under "Subcommands:".
std::set<std::string> subcommands() {
    std::set<std::string> names;
    std::istringstream help(helpText(""));
    bool inList = false;
    for (std::string line; std::getline(help, line);) {
        if (line.rfind("Subcommands:", 0) == 0) {
            inList = true;
            continue;
        }
        if (!inList || line.empty() || line[0] != ' ') continue;
        std::istringstream words(line);
        std::string name;
        words >> name;
        names.insert(name);
    }
    return names;
}

// The flags a line documents for `iblbake SUB`: its code spans' usages, and, under a heading naming the
// subcommand (cli.md's sections), the flags of a table row's first cell.
std::vector<std::pair<std::string, std::string>> documentedFlags(const DocLine& line) {
    std::vector<std::pair<std::string, std::string>> out; // subcommand, flag ("" for the bare subcommand)
    for (const std::string& span : line.codeSpans)
        for (const Usage& usage : usagesIn(span)) {
            out.emplace_back(usage.subcommand, "");
            for (const std::string& flag : usage.flags)
                out.emplace_back(usage.subcommand, flag);
        }
    static const std::regex section(R"(^`?iblbake ([a-z][a-z0-9-]*))");
    std::smatch heading;
    const bool tableRow = !line.inFence && line.text.rfind("| ", 0) == 0 && line.text.rfind("|---", 0) != 0;
    if (tableRow && std::regex_search(line.heading, heading, section)) {
        const std::string firstCell = line.text.substr(2, line.text.find(" |", 1) - 2);
        for (const std::string& flag : flagsIn(firstCell))
            out.emplace_back(heading[1].str(), flag);
    }
    return out;
}

// ---------------------------------------------------------------------------------------------------------
// Scene keys

// A scene every documented key can be tried in: each array holds one element of each shape, each object the
// documented containers, so that a key the parser knows is read (and then accepted, or refused for its value)
// and a key it does not know is left over as "unknown key".
json baseScene() {
    return json::parse(R"({
      "environment": {"file": "sky.hdr", "calibration": {"scale": 1}},
      "probes": [
        {"name": "a", "capture": "a.hdr", "position": [0, 0, 0],
         "proxy": {"shape": "box", "halfExtents": [1, 1, 1]}, "influence": {"shape": "sphere", "radius": 2}},
        {"name": "b", "capture": "b.hdr", "position": [0, 0, 0],
         "proxy": {"shape": "sphere", "radius": 1}, "influence": {"shape": "box", "halfExtents": [2, 2, 2]}}],
      "lights": [
        {"name": "s", "shape": "sphere", "lumens": 100},
        {"name": "d", "shape": "disk", "lumens": 100},
        {"name": "r", "shape": "rectangle", "lumens": 100}],
      "materials": {"roughness": {"min": 0, "max": 1}},
      "outputs": {"directory": "out", "gltf": {}, "preview": {}}
    })");
}

// parseScene's error for `scene`, or "" when it parses.
std::string parseError(const json& scene) {
    try {
        ibl::parseScene(scene.dump(), "scene.json", kSource);
        return "";
    } catch (const ibl::Error& e) {
        return e.what();
    }
}

// The key path's parts: "probes[i].proxy.radius" -> {"probes[]", "proxy", "radius"}.
std::vector<std::string> keyParts(const std::string& path) {
    std::vector<std::string> parts;
    std::istringstream in(path);
    for (std::string part; std::getline(in, part, '.');) {
        const std::size_t bracket = part.find('[');
        parts.push_back(bracket == std::string::npos ? part : part.substr(0, bracket) + "[]");
    }
    return parts;
}

// Places `path` in `scene` (null where absent; arrays: the element `choice` picks, modulo their size);
// false when a container on the way is not an object or array of the base scene.
bool placeKey(json& scene, const std::vector<std::string>& parts, std::size_t choice) {
    json* at = &scene;
    for (std::size_t i = 0; i < parts.size(); ++i) {
        const bool array = parts[i].size() > 2 && parts[i].compare(parts[i].size() - 2, 2, "[]") == 0;
        const std::string name = array ? parts[i].substr(0, parts[i].size() - 2) : parts[i];
        if (!at->is_object()) return false;
        if (i + 1 == parts.size() && !array) {
            if (!at->contains(name)) (*at)[name] = nullptr;
            return true;
        }
        json& next = (*at)[name];
        if (array) {
            if (!next.is_array() || next.empty()) return false;
            at = &next[choice % next.size()];
        } else {
            if (next.is_null()) next = json::object();
            at = &next;
        }
    }
    return true;
}

// Whether parseScene knows the key: in some element of the base scene's arrays, placing it leaves no
// "unknown key" (a refusal of its null value is fine: the parser read the key).
std::string unknownKeyError(const std::string& path) {
    const std::vector<std::string> parts = keyParts(path);
    std::string error = "it cannot be placed in a scene";
    for (std::size_t choice = 0; choice < 3; ++choice) {
        json scene = baseScene();
        if (!placeKey(scene, parts, choice)) continue;
        error = parseError(scene);
        if (error.find(": unknown key") == std::string::npos) return "";
    }
    return error;
}

// The documented keys of docs/scenes.md: the first cell of each row of the table under "Schema".
std::vector<std::pair<DocLine, std::string>> documentedSceneKeys() {
    std::vector<std::pair<DocLine, std::string>> keys;
    static const std::regex row(R"(^\| `([^`]+)` \|)");
    for (const DocLine& line : readDoc(kSource / "docs" / "scenes.md")) {
        std::smatch m;
        if (line.heading == "Schema" && !line.inFence && std::regex_search(line.text, m, row))
            keys.emplace_back(line, m[1].str());
    }
    return keys;
}

// ---------------------------------------------------------------------------------------------------------
// Links and citations

// GitHub's anchor of a heading: lower case, punctuation dropped, spaces as hyphens.
std::string anchorOf(const std::string& heading) {
    std::string anchor;
    for (char ch : heading) {
        const auto c = static_cast<unsigned char>(ch);
        if (std::isalnum(c) || ch == '-' || ch == '_')
            anchor += char(std::tolower(c));
        else if (ch == ' ')
            anchor += '-';
    }
    return anchor;
}

// The headings of a Markdown file, backticks removed.
std::set<std::string> headingsOf(const fs::path& file) {
    std::set<std::string> headings;
    for (const DocLine& line : readDoc(file))
        if (!line.inFence && line.text.rfind('#', 0) == 0) {
            std::string text = line.text.substr(line.text.find_first_not_of("# "));
            text.erase(std::remove(text.begin(), text.end(), '`'), text.end());
            headings.insert(text);
        }
    return headings;
}

std::string linkError(const fs::path& doc, const std::string& target) {
    const std::size_t hash = target.find('#');
    const fs::path file = (doc.parent_path() / target.substr(0, hash)).lexically_normal();
    if (!fs::exists(file)) return "no file " + file.lexically_relative(kSource).string();
    if (hash == std::string::npos || file.extension() != ".md") return "";
    for (const std::string& heading : headingsOf(file))
        if (anchorOf(heading) == target.substr(hash + 1)) return "";
    return "no heading with anchor #" + target.substr(hash + 1) + " in " +
           file.lexically_relative(kSource).string();
}

} // namespace

TEST(Docs, ReadmeIsAFiveMinuteRead) {
    std::ifstream in(kSource / "README.md");
    int lines = 0;
    for (std::string line; std::getline(in, line);)
        ++lines;
    EXPECT_LE(lines, 300) << "README.md has " << lines << " lines; move detail into docs/";
}

TEST(Docs, DocumentedSubcommandsAndFlagsExist) {
    const std::set<std::string> known = subcommands();
    ASSERT_GE(known.size(), 10u) << "`iblbake --help` lists no subcommands:\n" << helpText("");
    int checked = 0;
    for (const fs::path& file : docFiles())
        for (const DocLine& line : readDoc(file))
            for (const auto& [subcommand, flag] : documentedFlags(line)) {
                if (!known.count(subcommand)) { // once per usage: its flags cannot be checked
                    if (flag.empty())
                        ADD_FAILURE()
                            << where(line) << ": `iblbake " << subcommand << "` is no subcommand of iblbake";
                    continue;
                }
                if (flag.empty()) continue;
                ++checked;
                EXPECT_TRUE(helpHasFlag(helpText(subcommand), flag))
                    << where(line) << ": `iblbake " << subcommand << " " << flag << "`: `iblbake "
                    << subcommand << " --help` has no " << flag;
            }
    EXPECT_GE(checked, 100) << "the docs' flag usages were not found (cli.md's tables?)";
}

TEST(Docs, DocumentedSceneKeysAreParsed) {
    ASSERT_EQ(parseError(baseScene()), "") << "the test's base scene must parse";
    const auto keys = documentedSceneKeys();
    EXPECT_GE(keys.size(), 60u) << "docs/scenes.md's Schema table was not found";
    for (const auto& [line, key] : keys) {
        const std::string error = unknownKeyError(key);
        EXPECT_EQ(error, "") << where(line) << ": scene key `" << key
                             << "` is not accepted by parseScene: " << error;
    }
}

// A made-up key must fail the check above (so that it can fail).
TEST(Docs, AnUnknownSceneKeyIsCaught) {
    EXPECT_NE(unknownKeyError("probes[i].proxy.colour"), "");
    EXPECT_NE(unknownKeyError("outputs.gltf.size"), "");
    EXPECT_EQ(unknownKeyError("probes[i].proxy.radius"), "");
}

TEST(Docs, RelativeLinksPointAtFilesAndHeadings) {
    static const std::regex link(R"(\]\(([^)\s]+)\))");
    for (const fs::path& file : docFiles())
        for (const DocLine& line : readDoc(file)) {
            if (line.inFence) continue;
            for (auto it = std::sregex_iterator(line.text.begin(), line.text.end(), link);
                 it != std::sregex_iterator(); ++it) {
                const std::string target = (*it)[1].str();
                if (target.rfind("http://", 0) == 0 || target.rfind("https://", 0) == 0 ||
                    target.rfind("mailto:", 0) == 0)
                    continue;
                const std::string error = target[0] == '#'
                                              ? linkError(file, file.filename().string() + target)
                                              : linkError(file, target);
                EXPECT_EQ(error, "") << where(line) << ": link " << target;
            }
        }
}

// Comments, messages and help texts cite a section as docs/NAME.md "Heading" (or README "Heading"): the
// document must have that heading.
TEST(Docs, SourceCitationsNameExistingSections) {
    static const std::regex citation(R"((docs/[a-z_]+\.md|(?:^|[^/\w.])README(?:\.md)?) \\?"([^"\\]+)\\?")");
    int checked = 0;
    for (const char* folder : {"baker", "cli", "kernels", "tests", "cmake", "fuzz", "data", "docs"})
        for (const auto& entry : fs::recursive_directory_iterator(kSource / folder)) {
            if (!entry.is_regular_file() || entry.path().filename() == "test_docs.cpp") continue;
            const std::string ext = entry.path().extension().string();
            if (ext != ".h" && ext != ".cpp" && ext != ".cl" && ext != ".cmake" && ext != ".md" &&
                ext != ".txt" && ext != ".mjs" && ext != ".sh")
                continue;
            std::ifstream in(entry.path());
            int number = 0;
            for (std::string text; std::getline(in, text);) {
                ++number;
                for (auto it = std::sregex_iterator(text.begin(), text.end(), citation);
                     it != std::sregex_iterator(); ++it) {
                    std::string doc = (*it)[1].str();
                    doc = doc.find("docs/") == 0 ? doc : "README.md";
                    ++checked;
                    EXPECT_TRUE(headingsOf(kSource / doc).count((*it)[2].str()))
                        << entry.path().lexically_relative(kSource).string() << ":" << number << ": cites "
                        << doc << " \"" << (*it)[2].str() << "\", which has no such heading";
                }
            }
        }
    EXPECT_GE(checked, 20) << "no citations found";
}
