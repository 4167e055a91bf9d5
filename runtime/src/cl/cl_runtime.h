// Private: thin, checked OpenCL 1.2 plumbing. Every call's failure becomes a Status naming the call
// and the error code (CLBlast style); objects are owned by small RAII handles.
#pragma once

#define CL_TARGET_OPENCL_VERSION 120
#include <CL/cl.h>

#include <string>
#include <utility>
#include <vector>

#include "terrasynth/status.h"

namespace terrasynth::cl {

const char* errorName(cl_int code);

// Returns from the enclosing function with a Status naming the call when it fails.
#define TS_CL_CHECK(call)                                                                              \
    do {                                                                                               \
        const cl_int ts_cl_err_ = (call);                                                              \
        if (ts_cl_err_ != CL_SUCCESS)                                                                  \
            return ::terrasynth::Status::error(std::string("OpenCL: ") + #call + " failed: " +        \
                                               ::terrasynth::cl::errorName(ts_cl_err_));               \
    } while (0)

// For calls that report through an out-parameter: TS_CL_CHECK_NAMED(err, "clCreateKernel(correct)").
#define TS_CL_CHECK_NAMED(err, what)                                                                   \
    do {                                                                                               \
        if ((err) != CL_SUCCESS)                                                                       \
            return ::terrasynth::Status::error(std::string("OpenCL: ") + (what) + " failed: " +       \
                                               ::terrasynth::cl::errorName(err));                      \
    } while (0)

template <class T, cl_int (*Release)(T)>
class Handle {
public:
    Handle() = default;
    explicit Handle(T h) : h_(h) {}
    ~Handle() { reset(); }
    Handle(Handle&& o) noexcept : h_(std::exchange(o.h_, nullptr)) {}
    Handle& operator=(Handle&& o) noexcept {
        if (this != &o) {
            reset();
            h_ = std::exchange(o.h_, nullptr);
        }
        return *this;
    }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;
    T get() const { return h_; }
    T* out() { reset(); return &h_; }
    void reset() {
        if (h_) Release(h_);
        h_ = nullptr;
    }
    explicit operator bool() const { return h_ != nullptr; }

private:
    T h_ = nullptr;
};

using ContextHandle = Handle<cl_context, clReleaseContext>;
using QueueHandle = Handle<cl_command_queue, clReleaseCommandQueue>;
using ProgramHandle = Handle<cl_program, clReleaseProgram>;
using KernelHandle = Handle<cl_kernel, clReleaseKernel>;
using BufferHandle = Handle<cl_mem, clReleaseMemObject>;

struct DeviceChoice {
    cl_platform_id platform = nullptr;
    cl_device_id device = nullptr;
    std::string name;  // "platform / device"
};

// "" picks the first GPU, else the first device of any type; otherwise the first device whose
// platform or device name contains `hint`. TERRASYNTH_OPENCL_DEVICE overrides `hint`.
Result<DeviceChoice> chooseDevice(const std::string& hint);

// Source of kernels/<file_name>: the file in $TERRASYNTH_KERNEL_DIR when that is set (development),
// else the copy baked into the binary.
Result<std::string> kernelSource(const std::string& file_name);

// Builds a program from the named kernel files concatenated in order; a failure carries the log.
Result<ProgramHandle> buildProgram(cl_context context, cl_device_id device, const std::vector<std::string>& files,
                                   const std::string& options);

// A global work size: `value` rounded up to a multiple of the work-group size (PoCL requires it).
inline size_t roundUp(size_t value, size_t multiple) { return (value + multiple - 1) / multiple * multiple; }

// Where a buffer's memory is the host's (a CPU device, `huge_pages` set), large buffers live in
// whole 2 MiB pages of the host's, advised for transparent huge pages before anything touches them
// (CL_MEM_USE_HOST_PTR, freed when the driver releases the buffer): a 1024^2 synthesis writes
// state buffers of 18 MB and reads a database atlas of up to hundreds of MB, and with 4 KiB pages
// a fresh process spent about a fifteenth of its synthesis in page faults (docs/benchmarks.md,
// "Huge pages"). For GPU drivers buffers are the driver's as before. Contents
// and results are the same either way.
struct HostMemory {
    bool huge_pages = false;  // set for CPU devices only
};

// Buffers of at least this many bytes get huge pages (smaller ones would waste most of one).
constexpr size_t kHugePageAdviceBytes = size_t{2} << 20;

// A new buffer of `bytes` (`access`: CL_MEM_READ_ONLY, ...), with `data` copied in when not null; a
// failure names `what`.
Result<BufferHandle> createBuffer(cl_context context, const HostMemory& memory, cl_mem_flags access, const void* data,
                                  size_t bytes, const char* what);

// Grows `buffer` (read-write, uninitialised) to at least `bytes`, `capacity` its size in bytes;
// never shrinks, so windows of one size reuse it. A failure names `what` and the size.
Status reserveBuffer(cl_context context, BufferHandle& buffer, size_t& capacity, size_t bytes, const char* what,
                     const HostMemory& memory = {});

// Sets kernel arguments in order, each checked; the message names the kernel and argument index.
class ArgSetter {
public:
    ArgSetter(cl_kernel kernel, const char* name) : kernel_(kernel), name_(name) {}
    template <class T>
    ArgSetter& operator()(const T& value) {
        if (status_.isOk()) {
            const cl_int err = clSetKernelArg(kernel_, index_, sizeof(T), &value);
            if (err != CL_SUCCESS)
                status_ = Status::error(std::string("OpenCL: clSetKernelArg(") + name_ + ", " + std::to_string(index_) +
                                        ") failed: " + errorName(err));
        }
        ++index_;
        return *this;
    }
    const Status& status() const { return status_; }

private:
    cl_kernel kernel_;
    const char* name_;
    cl_uint index_ = 0;
    Status status_ = Status::ok();
};

}  // namespace terrasynth::cl
