// Private: the drainage breach (synth/drainage_breach.h) on the OpenCL device, kernels/drainage.cl.
// The same results as synth::breachPits, bit for bit (the kernels repeat its float operations in
// its order; cl_drainage_internal_test compares them), with the level's state left on the device:
// no read-back or map per level. On a GPU the host's search took many times the synthesis.
#pragma once

#include <string>
#include <vector>

#include "cl/cl_runtime.h"
#include "synth/drainage_breach.h"

namespace terrasynth::cl {

// Build options (-D) that kernels/drainage.cl takes from synth/drainage_breach.h.
std::string drainageDefines();

// The database level the breach reads, on the device.
struct DrainageLevelBuffers {
    cl_mem heights = nullptr;   // float per atlas pixel (DatabaseLevel::height_m)
    cl_mem exemplar = nullptr;  // uchar per atlas pixel
    // uchar per atlas pixel (DatabaseLevel::closed), closed_pixels of them; at least one byte, zeros
    // when the database has no flags (closed_pixels 0).
    cl_mem closed = nullptr;
    cl_int width = 0;
    cl_uint atlas_pixels = 0, closed_pixels = 0;
    cl_mem level_ground = nullptr;  // uchar per atlas pixel (synth::levelGroundFlags); null: none
};

// synth::DrainageInputs with the per-pixel arrays the synthesizer already holds on the device.
struct DeviceDrainageInputs {
    cl_mem coherence = nullptr;                   // W codes per region pixel; null: none frozen
    cl_mem blend = nullptr;                       // float4 constraint sums per region pixel; null: none
    const synth::PassHistory* drained = nullptr;  // uploaded when it holds the region's pixels
    float depth_margin = 0.0f;
    bool carve_to_edge = false;
    synth::LevelRegion needed;                    // empty: the whole region
    const std::vector<uint8_t>* basin_exemplars = nullptr;  // uploaded once (they are the database's)
    float level_tolerance = 0.0f;                           // synth::DrainageInputs::level_tolerance
};

// Kernels and scratch buffers of the device breach; one per synthesizer (not thread-safe). Scratch
// grows to the largest level breached and is kept.
class DeviceBreach {
public:
    // `program` holds kernels/drainage.cl, built with drainageDefines().
    Status initialise(cl_context context, cl_device_id device, cl_program program);

    // Breaches the pits of `state` (region.pixels() float4s, PixelState layout) in place, as
    // synth::breachPits does on the host; enqueued on `queue`, nothing waits for it.
    Status run(cl_command_queue queue, const DrainageLevelBuffers& level, const synth::LevelRegion& region, int radius,
               const DeviceDrainageInputs& inputs, cl_mem state);

private:
    Status reserve(BufferHandle& buffer, size_t& capacity, size_t bytes, const char* what);
    Status reserveSearch(cl_command_queue queue, size_t workers, size_t cells);
    Result<BufferHandle> upload(const void* data, size_t bytes, const char* what);

    cl_context context_ = nullptr;
    KernelHandle prepare_, row_min_, flag_, list_, search_, apply_;
    bool gpu_ = false;
    size_t compute_units_ = 1;
    BufferHandle z_, fixed_, carve_, row_minima_, pits_, pit_flags_, carved_, counters_, placeholder_;
    size_t z_bytes_ = 0, fixed_bytes_ = 0, carve_bytes_ = 0, row_min_bytes_ = 0, pits_bytes_ = 0, pit_flags_bytes_ = 0,
           carved_bytes_ = 0;
    // The searches' scratch (drainage.cl, Scratch), for search_cells_ cells.
    BufferHandle cost_, mark_cells_, parent_, heap_pos_, heap_;
    size_t search_cells_ = 0;
    // Each search numbers its marks with a serial of its own, so no search clears its window.
    cl_uint serial_base_ = 1;
    BufferHandle basins_;
    std::vector<uint8_t> uploaded_basins_;
    bool basins_uploaded_ = false;
};

}  // namespace terrasynth::cl
