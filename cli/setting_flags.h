// The flags that set the library's settings: a library error about a setting (ibl::SettingError) says
// what is wrong; the CLI puts the flag that caused it in front.
#pragma once

#include <iblbake/core/error.h>

#include <string>

namespace ibl::cli {

// The flag that sets `setting` (SettingError::setting()), or "" for one that no single flag sets (the
// calibration value: its flag depends on the source, calibration_options.h withFlag).
std::string flagOf(const std::string& setting);

// "<flag>: <message>", or the message alone when flagOf gives no flag.
std::string flaggedMessage(const SettingError& error);

} // namespace ibl::cli
