#include "cl/cl_drainage.h"

#include <algorithm>
#include <cstdio>

namespace terrasynth::cl {
namespace {

// A float as an exact OpenCL C literal (hexadecimal), so the kernels use the host's very value.
std::string exactLiteral(float value) {
    char text[48];
    std::snprintf(text, sizeof text, "%af", static_cast<double>(value));
    return text;
}

struct RegionArg {
    cl_int x, y, width, height;
};
struct SpanArg {
    cl_int x0, y0, x1, y1;  // inclusive
};

// Bytes of search scratch per window cell: cost, mark, parent step, heap place, heap entry.
constexpr size_t kSearchBytesPerCell = sizeof(cl_float) + sizeof(cl_uint) + 1 + sizeof(cl_int) + sizeof(cl_ulong);
// GPU: searches per compute unit (one warp), and the most scratch they may take. A level's few
// long searches (up to 3600 cells settled at level 4 of a 1024^2 synthesis) set its time, so
// they should not share a unit; the level-4 window (65^2 cells) takes 89 kB per search, and
// 192 MB hold about 2100 at once, more than that level has pits. CPU: one search per core.
constexpr size_t kGpuSearchesPerUnit = 32, kGpuSearchLocal = 32;
constexpr size_t kGpuSearchScratchBytes = size_t{192} << 20;
// breach counters: pits listed, pits taken, pixels carved.
constexpr size_t kCounters = 3;
// Serials are doubled into marks (reached / settled), so they stay below 2^31.
constexpr cl_uint kSerialLimit = 0x7fffffffu;

// Work-group shapes: per pixel, per row.
const size_t kLocal2d[2] = {32, 2};
constexpr size_t kRowLocal = 32;

// Windows up to this radius take their minimum straight from the heights, wider ones from row
// minima (as breachPits; only the work depends on it).
constexpr int kDirectMinimumRadius = 8;

Status run1d(cl_command_queue queue, cl_kernel kernel, size_t count, size_t local) {
    const size_t global = roundUp(count, local);
    TS_CL_CHECK(clEnqueueNDRangeKernel(queue, kernel, 1, nullptr, &global, &local, 0, nullptr, nullptr));
    return Status::ok();
}

Status run2d(cl_command_queue queue, cl_kernel kernel, size_t width, size_t height) {
    if (width == 0 || height == 0) return Status::ok();
    const size_t global[2] = {roundUp(width, kLocal2d[0]), roundUp(height, kLocal2d[1])};
    TS_CL_CHECK(clEnqueueNDRangeKernel(queue, kernel, 2, nullptr, global, kLocal2d, 0, nullptr, nullptr));
    return Status::ok();
}

}  // namespace

std::string drainageDefines() {
    return " -DBREACH_EDGE_DROP=" + exactLiteral(synth::kEdgeDrop) + " -DBREACH_STEP_COST=" +
           exactLiteral(synth::kBreachStepCost) + " -DDIAGONAL_LENGTH=" + exactLiteral(synth::kBreachDiagonal) +
           " -DBREACH_PROFILE_DEPTH=" + exactLiteral(synth::kBreachProfileDepth);
}

Status DeviceBreach::initialise(cl_context context, cl_device_id device, cl_program program) {
    context_ = context;
    cl_int err = CL_SUCCESS;
    for (auto [handle, name] : {std::pair{&prepare_, "breach_prepare"}, std::pair{&row_min_, "breach_row_min"},
                                std::pair{&flag_, "breach_pit_flags"}, std::pair{&list_, "breach_list_pits"},
                                std::pair{&search_, "breach_search"},
                                std::pair{&apply_, "breach_apply"}}) {
        *handle->out() = clCreateKernel(program, name, &err);
        TS_CL_CHECK_NAMED(err, std::string("clCreateKernel(") + name + ")");
    }
    cl_device_type type = 0;
    TS_CL_CHECK(clGetDeviceInfo(device, CL_DEVICE_TYPE, sizeof type, &type, nullptr));
    gpu_ = (type & CL_DEVICE_TYPE_GPU) != 0;
    cl_uint units = 1;
    TS_CL_CHECK(clGetDeviceInfo(device, CL_DEVICE_MAX_COMPUTE_UNITS, sizeof units, &units, nullptr));
    compute_units_ = std::max<cl_uint>(units, 1);
    auto placeholder = upload(nullptr, 0, "placeholder");
    if (!placeholder) return placeholder.status();
    placeholder_ = std::move(placeholder.value());
    auto counters = upload(nullptr, kCounters * sizeof(cl_int), "breach counters");
    if (!counters) return counters.status();
    counters_ = std::move(counters.value());
    return Status::ok();
}

Result<BufferHandle> DeviceBreach::upload(const void* data, size_t bytes, const char* what) {
    static const cl_int kZeros[4] = {};
    if (bytes == 0) bytes = sizeof kZeros;  // every argument a valid object
    if (!data) data = kZeros;
    cl_int err = CL_SUCCESS;
    BufferHandle buffer(clCreateBuffer(context_, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, bytes, const_cast<void*>(data), &err));
    TS_CL_CHECK_NAMED(err, std::string("clCreateBuffer(") + what + ", " + std::to_string(bytes) + " bytes)");
    return buffer;
}

Status DeviceBreach::reserve(BufferHandle& buffer, size_t& capacity, size_t bytes, const char* what) {
    return reserveBuffer(context_, buffer, capacity, std::max<size_t>(bytes, 16), what);  // never an empty buffer
}

Status DeviceBreach::reserveSearch(cl_command_queue queue, size_t workers, size_t cells) {
    const size_t needed = workers * cells;
    if (search_cells_ >= needed && cost_) return Status::ok();
    for (auto [buffer, bytes, what] : {std::tuple{&cost_, sizeof(cl_float), "breach search cost"},
                                      std::tuple{&mark_cells_, sizeof(cl_uint), "breach search marks"},
                                      std::tuple{&parent_, size_t{1}, "breach search steps"},
                                      std::tuple{&heap_pos_, sizeof(cl_int), "breach search heap places"},
                                      std::tuple{&heap_, sizeof(cl_ulong), "breach search heap"}}) {
        buffer->reset();  // before the next allocation: the old and the new need not both fit
        size_t capacity = 0;
        Status s = reserve(*buffer, capacity, needed * bytes, what);
        if (!s) return s;
    }
    search_cells_ = needed;
    // No mark may equal a live search's: fresh marks are 0, and serials start at 1.
    const cl_uint zero = 0;
    TS_CL_CHECK(clEnqueueFillBuffer(queue, mark_cells_.get(), &zero, sizeof zero, 0, needed * sizeof(cl_uint), 0, nullptr, nullptr));
    serial_base_ = 1;
    return Status::ok();
}

Status DeviceBreach::run(cl_command_queue queue, const DrainageLevelBuffers& level, const synth::LevelRegion& region,
                         int radius, const DeviceDrainageInputs& inputs, cl_mem state) {
    const int w = region.width, h = region.height;
    const size_t pixels = region.pixels();
    if (pixels == 0) return Status::ok();
    // Pits that can reach the needed pixels (interior pixels only), and the zone the searches read:
    // within radius + 1 of them (breachPits).
    int x0 = 1, y0 = 1, x1 = w - 2, y1 = h - 2;
    if (inputs.needed.width > 0 && inputs.needed.height > 0) {
        x0 = std::max(x0, inputs.needed.x - region.x - radius), y0 = std::max(y0, inputs.needed.y - region.y - radius);
        x1 = std::min(x1, inputs.needed.x - region.x + inputs.needed.width - 1 + radius);
        y1 = std::min(y1, inputs.needed.y - region.y + inputs.needed.height - 1 + radius);
    }
    const SpanArg span{x0, y0, x1, y1};
    const SpanArg zone{std::max(0, x0 - radius - 1), std::max(0, y0 - radius - 1), std::min(w - 1, x1 + radius + 1),
                       std::min(h - 1, y1 + radius + 1)};
    const bool any_pits = x0 <= x1 && y0 <= y1;
    const bool use_row_min = radius > kDirectMinimumRadius;
    const bool use_fixed = inputs.coherence || inputs.blend;  // else nothing is protected
    for (auto [buffer, capacity, bytes, what] :
         {std::tuple{&z_, &z_bytes_, pixels * sizeof(cl_float), "breach heights"},
          std::tuple{&fixed_, &fixed_bytes_, use_fixed ? pixels : 0, "breach protected pixels"},
          std::tuple{&carve_, &carve_bytes_, pixels * sizeof(cl_int), "breach carves"},
          std::tuple{&pits_, &pits_bytes_, pixels * sizeof(cl_int), "breach pits"},
          std::tuple{&pit_flags_, &pit_flags_bytes_, pixels, "breach pit flags"},
          std::tuple{&carved_, &carved_bytes_, pixels * sizeof(cl_int), "breach carved pixels"},
          std::tuple{&row_minima_, &row_min_bytes_, use_row_min ? pixels * sizeof(cl_float) : 0, "breach row minima"}}) {
        Status s = reserve(*buffer, *capacity, bytes, what);
        if (!s) return s;
    }
    if (inputs.basin_exemplars && (!basins_uploaded_ || uploaded_basins_ != *inputs.basin_exemplars)) {
        auto basins = upload(inputs.basin_exemplars->data(), inputs.basin_exemplars->size(), "basin exemplars");
        if (!basins) return basins.status();
        basins_ = std::move(basins.value());
        uploaded_basins_ = *inputs.basin_exemplars;
        basins_uploaded_ = true;
    }
    const cl_uint basin_count = inputs.basin_exemplars ? static_cast<cl_uint>(inputs.basin_exemplars->size()) : 0;
    const bool use_drained = inputs.drained && inputs.drained->index.size() == pixels && inputs.drained->v.size() == pixels;
    BufferHandle drained_index, drained_v;
    if (use_drained) {
        auto index = upload(inputs.drained->index.data(), pixels * sizeof(cl_uint), "drained index");
        if (!index) return index.status();
        auto v = upload(inputs.drained->v.data(), pixels * sizeof(cl_float), "drained offsets");
        if (!v) return v.status();
        drained_index = std::move(index.value()), drained_v = std::move(v.value());
    }
    const RegionArg region_arg{region.x, region.y, w, h};
    cl_mem placeholder = placeholder_.get();

    ArgSetter prepare(prepare_.get(), "breach_prepare");
    prepare(state)(region_arg)(z_.get())(fixed_.get())(cl_int{use_fixed ? 1 : 0})(carve_.get())(zone)(level.heights)(level.width)(
        inputs.coherence ? inputs.coherence : placeholder)(cl_int{inputs.coherence ? 1 : 0})(
        use_drained ? drained_index.get() : placeholder)(use_drained ? drained_v.get() : placeholder)(
        cl_int{use_drained ? 1 : 0})(inputs.blend ? inputs.blend : placeholder)(cl_int{inputs.blend ? 1 : 0});
    if (!prepare.status()) return prepare.status();
    Status s = run2d(queue, prepare_.get(), w, h);
    if (!s) return s;

    if (any_pits) {
        if (use_row_min) {
            ArgSetter rows(row_min_.get(), "breach_row_min");
            rows(z_.get())(region_arg)(zone)(cl_int{radius})(row_minima_.get());
            if (!rows.status()) return rows.status();
            s = run1d(queue, row_min_.get(), zone.y1 - zone.y0 + 1, kRowLocal);
            if (!s) return s;
        }
        const cl_int zero = 0;
        TS_CL_CHECK(clEnqueueFillBuffer(queue, counters_.get(), &zero, sizeof zero, 0, kCounters * sizeof(cl_int), 0, nullptr, nullptr));
        ArgSetter flag(flag_.get(), "breach_pit_flags");
        // A database without the flags has a buffer of zeros (DrainageLevelBuffers::closed).
        flag(z_.get())(state)(region_arg)(span)(level.closed)(std::max<cl_uint>(level.closed_pixels, 1))(level.width)(
            pit_flags_.get());
        if (!flag.status()) return flag.status();
        s = run2d(queue, flag_.get(), x1 - x0 + 1, y1 - y0 + 1);
        if (!s) return s;
        ArgSetter list(list_.get(), "breach_list_pits");
        list(pit_flags_.get())(region_arg)(span)(pits_.get())(counters_.get());
        if (!list.status()) return list.status();
        s = run1d(queue, list_.get(), y1 - y0 + 1, kRowLocal);
        if (!s) return s;

        // Enough workers to keep the device busy, each with a window of scratch.
        const size_t side = 2 * static_cast<size_t>(radius) + 1, cells = side * side;
        size_t local = 1, workers = compute_units_;
        if (gpu_) {
            local = kGpuSearchLocal;
            const size_t affordable = kGpuSearchScratchBytes / (cells * kSearchBytesPerCell);
            workers = std::max(local, std::min(compute_units_ * kGpuSearchesPerUnit, affordable) / local * local);
        }
        s = reserveSearch(queue, workers, cells);
        if (!s) return s;
        const size_t searched = static_cast<size_t>(x1 - x0 + 1) * (y1 - y0 + 1);  // pits listed at most
        if (serial_base_ > kSerialLimit - searched) {
            const cl_uint zero = 0;
            TS_CL_CHECK(clEnqueueFillBuffer(queue, mark_cells_.get(), &zero, sizeof zero, 0,
                                            search_cells_ * sizeof(cl_uint), 0, nullptr, nullptr));
            serial_base_ = 1;
        }
        ArgSetter search(search_.get(), "breach_search");
        search(z_.get())(fixed_.get())(cl_int{use_fixed ? 1 : 0})(use_row_min ? row_minima_.get() : placeholder)(cl_int{use_row_min ? 1 : 0})(state)(
            region_arg)(cl_int{radius})(inputs.depth_margin)(cl_int{inputs.carve_to_edge ? 1 : 0})(level.exemplar)(
            level.atlas_pixels)(level.width)(basins_ ? basins_.get() : placeholder)(basin_count)(pits_.get())(
            counters_.get())(serial_base_)(cost_.get())(mark_cells_.get())(parent_.get())(heap_pos_.get())(heap_.get())(
            carve_.get())(carved_.get())(level.heights)(level.level_ground ? level.level_ground : placeholder)(
            cl_int{level.level_ground ? 1 : 0})(inputs.level_tolerance);
        if (!search.status()) return search.status();
        s = run1d(queue, search_.get(), workers, local);
        if (!s) return s;
        serial_base_ += static_cast<cl_uint>(searched);

        ArgSetter apply(apply_.get(), "breach_apply");
        apply(state)(z_.get())(carve_.get())(carved_.get())(counters_.get());
        if (!apply.status()) return apply.status();
        s = run1d(queue, apply_.get(), workers, local);
        if (!s) return s;
    }

    // The uploads above are released here while the kernels may still read them: OpenCL keeps a
    // buffer alive until the commands that use it have finished.
    return Status::ok();
}

}  // namespace terrasynth::cl
