#include "cl/cl_runtime.h"

#include <sys/mman.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>

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

namespace {

constexpr size_t kHugePage = size_t{2} << 20;

void CL_CALLBACK freeHostMemory(cl_mem, void* memory) { std::free(memory); }

}  // namespace

Result<BufferHandle> createBuffer(cl_context context, const HostMemory& memory, cl_mem_flags access, const void* data,
                                  size_t bytes, const char* what) {
    auto failed = [&](cl_int err) {
        return Status::error(std::string("OpenCL: clCreateBuffer(") + what + ", " + std::to_string(bytes) +
                             " bytes) failed: " + errorName(err));
    };
    cl_int err = CL_SUCCESS;
    if (!memory.huge_pages || bytes < kHugePageAdviceBytes) {
        BufferHandle buffer(clCreateBuffer(context, access | (data ? CL_MEM_COPY_HOST_PTR : 0), bytes,
                                           const_cast<void*>(data), &err));
        if (err != CL_SUCCESS) return failed(err);
        return buffer;
    }
    // Whole 2 MiB pages of our own, advised before anything touches them; the buffer uses them as
    // its storage (a CPU driver does not copy a CL_MEM_USE_HOST_PTR buffer) and frees them when
    // the driver releases it. The advice is a hint: where madvise refuses it, nothing changes.
    const size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
    void* host = std::aligned_alloc(kHugePage, rounded);
    if (!host) return Status::error(std::string("out of memory for ") + what + " (" + std::to_string(bytes) + " bytes)");
    (void)madvise(host, rounded, MADV_HUGEPAGE);
    if (data) std::memcpy(host, data, bytes);
    BufferHandle buffer(clCreateBuffer(context, access | CL_MEM_USE_HOST_PTR, bytes, host, &err));
    if (err != CL_SUCCESS) {
        std::free(host);
        return failed(err);
    }
    err = clSetMemObjectDestructorCallback(buffer.get(), freeHostMemory, host);
    if (err != CL_SUCCESS) {
        buffer.reset();  // the driver may still hold the pointer until it releases the buffer
        std::free(host);
        return Status::error(std::string("OpenCL: clSetMemObjectDestructorCallback(") + what + ") failed: " +
                             errorName(err));
    }
    return buffer;
}

Status reserveBuffer(cl_context context, BufferHandle& buffer, size_t& capacity, size_t bytes, const char* what,
                     const HostMemory& memory) {
    if (buffer && capacity >= bytes) return Status::ok();
    buffer.reset();  // before the next allocation: the old and the new need not both fit
    auto created = createBuffer(context, memory, CL_MEM_READ_WRITE, nullptr, bytes, what);
    if (!created) return created.status();
    buffer = std::move(created.value());
    capacity = bytes;
    return Status::ok();
}

}  // namespace terrasynth::cl
