// The backend choice by name. Header-only, without OpenCL: the front end (cli/front_end.cpp) and the
// up-to-date check need the names but never start a backend.
#pragma once

#include "iblbake/core/error.h"

#include <string>

namespace ibl {

enum class Backend { Auto, OpenCL, Cpu };

// "auto" | "opencl" | "cpu"; throws ibl::SettingError ("backend") otherwise.
inline Backend parseBackend(const std::string& name) {
    if (name == "auto") return Backend::Auto;
    if (name == "opencl") return Backend::OpenCL;
    if (name == "cpu") return Backend::Cpu;
    throw SettingError("backend", "'" + name + "' is not one of auto, opencl, cpu");
}

inline const char* backendName(Backend backend) {
    switch (backend) {
    case Backend::OpenCL:
        return "opencl";
    case Backend::Cpu:
        return "cpu";
    default:
        return "auto";
    }
}

} // namespace ibl
