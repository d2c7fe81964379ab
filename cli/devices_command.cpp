// iblbake devices: lists the OpenCL devices the host layer can choose from.
#include "commands.h"

#include <iblbake/opencl/opencl_context.h>

#include <cstdio>

namespace ibl::cli {

Action addDevicesCommand(CLI::App& app) {
    app.add_subcommand("devices", "list OpenCL platforms and devices");
    return [] {
        auto devices = ocl::listDevices();
        if (devices.empty()) {
            std::printf("no OpenCL device found; bakes run on the CPU backend\n");
            return 0;
        }
        for (const ocl::DeviceInfo& d : devices)
            std::printf("%s  %-11s %s | %s | %s | %u compute units | %.1f GiB\n", d.id().c_str(),
                        d.deviceType.c_str(), d.deviceName.c_str(), d.platformName.c_str(),
                        d.deviceVersion.c_str(), d.computeUnits,
                        double(d.globalMemBytes) / (1024.0 * 1024.0 * 1024.0));
        return 0;
    };
}

} // namespace ibl::cli
