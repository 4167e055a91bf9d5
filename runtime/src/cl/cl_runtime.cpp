#include "cl/cl_runtime.h"

#include <cstdlib>

#include "cl/baked_kernels.h"
#include "terrasynth/heightfield_io.h"

namespace terrasynth::cl {

const char* errorName(cl_int code) {
    switch (code) {
#define TS_CASE(c) case c: return #c;
        TS_CASE(CL_DEVICE_NOT_FOUND) TS_CASE(CL_DEVICE_NOT_AVAILABLE) TS_CASE(CL_COMPILER_NOT_AVAILABLE)
        TS_CASE(CL_MEM_OBJECT_ALLOCATION_FAILURE) TS_CASE(CL_OUT_OF_RESOURCES) TS_CASE(CL_OUT_OF_HOST_MEMORY)
        TS_CASE(CL_BUILD_PROGRAM_FAILURE) TS_CASE(CL_INVALID_VALUE) TS_CASE(CL_INVALID_DEVICE_TYPE)
        TS_CASE(CL_INVALID_PLATFORM) TS_CASE(CL_INVALID_DEVICE) TS_CASE(CL_INVALID_CONTEXT)
        TS_CASE(CL_INVALID_COMMAND_QUEUE) TS_CASE(CL_INVALID_MEM_OBJECT) TS_CASE(CL_INVALID_PROGRAM)
        TS_CASE(CL_INVALID_PROGRAM_EXECUTABLE) TS_CASE(CL_INVALID_KERNEL_NAME) TS_CASE(CL_INVALID_KERNEL)
        TS_CASE(CL_INVALID_ARG_INDEX) TS_CASE(CL_INVALID_ARG_VALUE) TS_CASE(CL_INVALID_ARG_SIZE)
        TS_CASE(CL_INVALID_KERNEL_ARGS) TS_CASE(CL_INVALID_WORK_DIMENSION) TS_CASE(CL_INVALID_WORK_GROUP_SIZE)
        TS_CASE(CL_INVALID_WORK_ITEM_SIZE) TS_CASE(CL_INVALID_GLOBAL_OFFSET) TS_CASE(CL_INVALID_BUFFER_SIZE)
        TS_CASE(CL_INVALID_GLOBAL_WORK_SIZE) TS_CASE(CL_INVALID_OPERATION)
#undef TS_CASE
        case -1001: return "CL_PLATFORM_NOT_FOUND_KHR (no OpenCL driver installed)";
        default: return "unknown OpenCL error";
    }
}

Result<DeviceChoice> chooseDevice(const std::string& requested) {
    const char* env = std::getenv("TERRASYNTH_OPENCL_DEVICE");
    const std::string hint = env && *env ? env : requested;
    cl_uint platform_count = 0;
    const cl_int err = clGetPlatformIDs(0, nullptr, &platform_count);
    if (err != CL_SUCCESS || platform_count == 0)
        return Status::error("no OpenCL platform found (install an OpenCL driver, e.g. pocl-opencl-icd): " +
                             std::string(err != CL_SUCCESS ? errorName(err) : "0 platforms"));
    std::vector<cl_platform_id> platforms(platform_count);
    TS_CL_CHECK(clGetPlatformIDs(platform_count, platforms.data(), nullptr));
    auto text = [](auto getter, auto object, cl_uint what) {
        size_t size = 0;
        getter(object, what, 0, nullptr, &size);
        std::string s(size, '\0');
        getter(object, what, size, s.data(), nullptr);
        while (!s.empty() && s.back() == '\0') s.pop_back();
        return s;
    };
    std::vector<DeviceChoice> all;
    for (cl_platform_id platform : platforms) {
        cl_uint count = 0;
        if (clGetDeviceIDs(platform, CL_DEVICE_TYPE_ALL, 0, nullptr, &count) != CL_SUCCESS || count == 0) continue;
        std::vector<cl_device_id> devices(count);
        TS_CL_CHECK(clGetDeviceIDs(platform, CL_DEVICE_TYPE_ALL, count, devices.data(), nullptr));
        const std::string platform_name = text(clGetPlatformInfo, platform, CL_PLATFORM_NAME);
        for (cl_device_id d : devices)
            all.push_back({platform, d, platform_name + " / " + text(clGetDeviceInfo, d, CL_DEVICE_NAME)});
    }
    if (all.empty()) return Status::error("OpenCL: no device on any platform");
    if (!hint.empty()) {
        for (const DeviceChoice& c : all)
            if (c.name.find(hint) != std::string::npos) return c;
        std::string names;
        for (const DeviceChoice& c : all) names += " [" + c.name + "]";
        return Status::error("OpenCL: no device matches \"" + hint + "\"; available:" + names);
    }
    for (const DeviceChoice& c : all) {
        cl_device_type type = 0;
        clGetDeviceInfo(c.device, CL_DEVICE_TYPE, sizeof(type), &type, nullptr);
        if (type & CL_DEVICE_TYPE_GPU) return c;
    }
    return all.front();
}

Result<std::string> kernelSource(const std::string& file_name) {
    const char* dir = std::getenv("TERRASYNTH_KERNEL_DIR");
    if (dir && *dir) {
        auto bytes = readFileBytes(std::string(dir) + "/" + file_name);
        if (!bytes) return Status::error("TERRASYNTH_KERNEL_DIR override: " + bytes.message());
        return bytes.value();
    }
    for (int i = 0; i < cl_detail::kBakedKernelCount; ++i)
        if (file_name == cl_detail::kBakedKernels[i].file_name) return std::string(cl_detail::kBakedKernels[i].source);
    return Status::error("kernel file " + file_name + " is not baked into this build");
}

Result<ProgramHandle> buildProgram(cl_context context, cl_device_id device, const std::vector<std::string>& files,
                                   const std::string& options) {
    std::string source;
    for (const std::string& f : files) {
        auto s = kernelSource(f);
        if (!s) return s.status();
        source += "#line 1 \"" + f + "\"\n" + s.value() + "\n";
    }
    const char* text = source.c_str();
    const size_t length = source.size();
    cl_int err = CL_SUCCESS;
    ProgramHandle program(clCreateProgramWithSource(context, 1, &text, &length, &err));
    TS_CL_CHECK_NAMED(err, "clCreateProgramWithSource");
    err = clBuildProgram(program.get(), 1, &device, options.c_str(), nullptr, nullptr);
    if (err != CL_SUCCESS) {
        size_t size = 0;
        clGetProgramBuildInfo(program.get(), device, CL_PROGRAM_BUILD_LOG, 0, nullptr, &size);
        std::string log(size, '\0');
        clGetProgramBuildInfo(program.get(), device, CL_PROGRAM_BUILD_LOG, size, log.data(), nullptr);
        return Status::error(std::string("OpenCL: clBuildProgram failed: ") + errorName(err) + "\n" + log);
    }
    return program;
}

Status reserveBuffer(cl_context context, BufferHandle& buffer, size_t& capacity, size_t bytes, const char* what) {
    if (buffer && capacity >= bytes) return Status::ok();
    cl_int err = CL_SUCCESS;
    *buffer.out() = clCreateBuffer(context, CL_MEM_READ_WRITE, bytes, nullptr, &err);
    TS_CL_CHECK_NAMED(err, std::string("clCreateBuffer(") + what + ", " + std::to_string(bytes) + " bytes)");
    capacity = bytes;
    return Status::ok();
}

}  // namespace terrasynth::cl
