#include "setting_flags.h"

#include <map>

namespace ibl::cli {

std::string flagOf(const std::string& setting) {
    // The library's setting names as its throwing functions document them, and the commands' flags.
    static const std::map<std::string, std::string> flags = {{"layout", "--layout"},
                                                             {"inputColorSpace", "--input-colorspace"},
                                                             {"workingColorSpace", "--working-colorspace"},
                                                             {"rotateDegrees", "--rotate"},
                                                             {"sourceFaceSize", "--size"},
                                                             {"latLongPixels", "--latlong-pixels"},
                                                             {"extractSun", "--extract-sun"},
                                                             {"mipMapping", "--mip-mapping"},
                                                             {"quality", "--quality"},
                                                             {"irradianceMethod", "--irradiance-method"},
                                                             {"irradianceFaceSize", "--irradiance-size"},
                                                             {"window", "--window"},
                                                             {"windowParameter", "--window-param"},
                                                             {"dfgSize", "--size"},
                                                             {"dfgSamples", "--samples"},
                                                             {"backend", "--backend"},
                                                             {"minFaceSize", "--min-face-size"},
                                                             {"intensity", "--intensity"},
                                                             {"faceSize", "--size"},
                                                             {"levels", "--levels"},
                                                             {"samples", "--samples"}};
    const auto it = flags.find(setting);
    return it == flags.end() ? std::string() : it->second;
}

std::string flaggedMessage(const SettingError& error) {
    const std::string flag = flagOf(error.setting());
    return flag.empty() ? std::string(error.what()) : flag + ": " + error.what();
}

} // namespace ibl::cli
