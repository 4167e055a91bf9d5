#include "opencl_check.h"

#include <string>
#include <vector>

#ifdef TERRASYNTH_GAME_HAVE_OPENCL
#define CL_TARGET_OPENCL_VERSION 120
#include <CL/cl.h>
#endif

namespace terrasynth::game {

Status checkOpenClDevice() {
#ifdef TERRASYNTH_GAME_HAVE_OPENCL
    cl_uint platforms = 0;
    const cl_int err = clGetPlatformIDs(0, nullptr, &platforms);
    if (err != CL_SUCCESS || platforms == 0)
        return Status::error("no OpenCL platform found (clGetPlatformIDs: " + std::to_string(err) +
                             "; is an ICD such as pocl-opencl-icd installed?)");
    std::vector<cl_platform_id> ids(platforms);
    if (clGetPlatformIDs(platforms, ids.data(), nullptr) != CL_SUCCESS)
        return Status::error("clGetPlatformIDs failed listing the platforms");
    for (cl_platform_id p : ids) {
        cl_uint devices = 0;
        if (clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, 0, nullptr, &devices) == CL_SUCCESS && devices > 0)
            return Status::ok();
    }
    return Status::error("no OpenCL device found on " + std::to_string(platforms) + " platform(s)");
#else
    return Status::error("this build has no OpenCL backend");
#endif
}

}  // namespace terrasynth::game
