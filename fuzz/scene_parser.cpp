// Fuzz target: the scene-file parser and the planner on arbitrary text (parseScene never touches the file
// system; relative paths are only resolved against the base directory). Seeds: fuzz/seeds/scene/.
#include "parser_target.h"

#include <iblbake/scene/scene.h>
#include <iblbake/scene/scene_plan.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return ibl::fuzz::parseOrRefuse(data, size, "fuzz.scene.json", [](auto bytes, const std::string& name) {
        const ibl::Scene scene =
            ibl::parseScene(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), name,
                            "/nonexistent");
        ibl::planScene(scene);
    });
}
