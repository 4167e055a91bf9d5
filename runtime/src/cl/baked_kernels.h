// Private: the kernels/*.cl sources compiled into the binary (see kernels/bake_kernels.cmake).
#pragma once

namespace terrasynth::cl_detail {

struct BakedKernel {
    const char* file_name;  // e.g. "synthesis.cl"
    const char* source;
};
extern const BakedKernel kBakedKernels[];
extern const int kBakedKernelCount;

}  // namespace terrasynth::cl_detail
