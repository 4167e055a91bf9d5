// The OpenCL backend: the database lives in device buffers (one set per pyramid level, the atlas of
// s4), the synthesis state in two buffers (current level and the one being upsampled into), and the
// shared driver (synth/synthesis_driver.h) enqueues kernels/synthesis.cl step by step.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <tuple>

#include "cl/cl_drainage.h"
#include "cl/cl_runtime.h"
#include "core/hash.h"
#include "cl/cl_synthesizer.h"
#include "synth/initial_patches.h"
#include "synth/level_ground.h"
#include "synth/reference_kernels.h"
#include "synth/synthesis_driver.h"
#include "synth/type_seeds.h"

namespace terrasynth {
namespace {

using cl::ArgSetter;
using cl::BufferHandle;
using cl::KernelHandle;

struct RegionArg {
    cl_int x, y, width, height;
};
RegionArg toArg(const synth::LevelRegion& r) { return {r.x, r.y, r.width, r.height}; }

struct DeviceLevel {
    BufferHandle appearance, candidates, exemplar, rects, heights, types, type_seeds, seed_ranges, closed;
    BufferHandle level_ground;  // synth::levelGroundFlags, uchar per atlas pixel
    cl_int width = 0;
    cl_uint pixels = 0, closed_pixels = 0;
    cl_float4 offset{}, scale{};
};

// Work-group shape: a tunable (TERRASYNTH_CL_LOCAL_SIZE="32,2"); results do not depend on it.
void localSize(size_t out[2]) {
    out[0] = 32;
    out[1] = 2;
    if (const char* env = std::getenv("TERRASYNTH_CL_LOCAL_SIZE")) {
        unsigned x = 0, y = 0;
        if (std::sscanf(env, "%u,%u", &x, &y) == 2 && x > 0 && y > 0) out[0] = x, out[1] = y;
    }
}

// A two-way runtime knob: true when the environment variable `name` is `yes`, false when `no`,
// else `fallback`.
bool envSwitch(const char* name, const char* yes, const char* no, bool fallback) {
    const char* env = std::getenv(name);
    if (!env) return fallback;
    if (std::string(env) == yes) return true;
    if (std::string(env) == no) return false;
    return fallback;
}

class OpenClSynthesizer final : public Synthesizer, private synth::SynthesisSteps {
public:
    explicit OpenClSynthesizer(std::shared_ptr<const ExemplarDatabase> db) : Synthesizer(std::move(db)) {}

    Status initialise(const SynthesizerOptions& options) {
        auto device = cl::chooseDevice(options.device);
        if (!device) return device.status();
        device_ = device.value();
        cl_int err = CL_SUCCESS;
        const cl_context_properties props[] = {CL_CONTEXT_PLATFORM,
                                               reinterpret_cast<cl_context_properties>(device_.platform), 0};
        *context_.out() = clCreateContext(props, 1, &device_.device, nullptr, nullptr, &err);
        TS_CL_CHECK_NAMED(err, "clCreateContext(" + device_.name + ")");
        *queue_.out() = clCreateCommandQueue(context_.get(), device_.device, 0, &err);
        TS_CL_CHECK_NAMED(err, "clCreateCommandQueue");
        // Paper constants come from constraints.h so host and kernels cannot disagree; divide and sqrt
        // are correctly rounded so the C++ reference can match the kernels.
        const std::string defines = "-cl-std=CL1.2 -cl-fp32-correctly-rounded-divide-sqrt -DSEEDS_PER_TYPE=" +
                                    std::to_string(kSeedsPerType) + " -DTOLERANCE_SLOPE=" +
                                    std::to_string(kPointToleranceSlope) + "f -DBLEND_SLOPE=" +
                                    std::to_string(kPointBlendSlope) + "f -DCOHERENT_WEIGHT=" +
                                    std::to_string(kCoherentWeight) + "f -DINIT_PATCH_SIZE=" +
                                    std::to_string(kInitialPatchSize) + " -DLAYOUT_WEIGHT=" + std::to_string(synth::kLayoutWeight) + "f" +
                                    cl::drainageDefines();
        cl_device_type type = 0;
        TS_CL_CHECK(clGetDeviceInfo(device_.device, CL_DEVICE_TYPE, sizeof type, &type, nullptr));
        const bool cpu_device = (type & CL_DEVICE_TYPE_CPU) != 0;
        // Whether `correct` prefetches its candidates (kernels/synthesis.cl, TS_CPU_PREFETCH): on CPU
        // devices, where it takes a fifth to a third off a synthesis. The same bits either way.
        const bool prefetch = envSwitch("TERRASYNTH_CL_PREFETCH", "on", "off", cpu_device);
        auto program = cl::buildProgram(context_.get(), device_.device, {"hash.cl", "synthesis.cl", "drainage.cl"},
                                        defines + (prefetch ? " -DTS_CPU_PREFETCH" : ""));
        if (!program) return program.status();
        program_ = std::move(program.value());
        for (auto [handle, name] : {std::pair{&init_cells_, "init_cells"}, std::pair{&init_, "init_level"},
                                    std::pair{&upsample_, "upsample_jitter"},
                                    std::pair{&correct_, "correct"}, std::pair{&resolve_, "resolve"}}) {
            *handle->out() = clCreateKernel(program_.get(), name, &err);
            TS_CL_CHECK_NAMED(err, std::string("clCreateKernel(") + name + ")");
        }
        Status breach = breach_.initialise(context_.get(), device_.device, program_.get());
        if (!breach) return breach;
        breach_on_device_ = envSwitch("TERRASYNTH_CL_BREACH", "device", "host", !cpu_device);
        // Huge pages for the large buffers of a CPU device (cl::HostMemory); `off` is for measuring.
        host_memory_.huge_pages = envSwitch("TERRASYNTH_CL_HUGE_PAGES", "on", "off", cpu_device);
        localSize(local_);
        auto placeholder = upload(nullptr, 0);
        if (!placeholder) return placeholder.status();
        placeholder_ = std::move(placeholder.value());
        return uploadDatabase();
    }

    Result<SynthesisOutput> synthesize(const PixelWindow& window, const SynthesisParams& params, int output_level,
                                       bool want_sources) override {
        size_t peak = 0;
        auto out = synth::runSynthesis(*db_, window, params, output_level, want_sources, *this, stop_requested_, &peak);
        if (out) {
            const double pixels = static_cast<double>(window.width) * window.height;
            bytes_per_pixel_ = (peak * sizeof(cl_float4) + pixels * (want_sources ? 13.0 : 4.0)) / pixels;
        }
        return out;
    }
    std::string deviceName() const override { return device_.name; }
    double lastBytesPerPixel() const override { return bytes_per_pixel_; }

private:
    Result<BufferHandle> upload(const void* data, size_t bytes) {
        // Empty arrays (no constraints, no history: the usual case per level and pass) share one
        // small buffer, so every kernel argument is a valid object without an allocation per call.
        static const float kPlaceholder[8] = {};
        if (bytes == 0 && placeholder_) {
            TS_CL_CHECK(clRetainMemObject(placeholder_.get()));
            return BufferHandle(placeholder_.get());
        }
        if (bytes == 0) data = kPlaceholder, bytes = sizeof(kPlaceholder);
        return cl::createBuffer(context_.get(), host_memory_, CL_MEM_READ_ONLY, data, bytes, "database");
    }

    Status uploadDatabase() {
        for (const DatabaseLevel& l : db_->levels) {
            DeviceLevel d;
            std::vector<cl_int4> rects;
            for (const AtlasRect& r : l.rects) rects.push_back({{r.x, r.y, r.width, r.height}});
            auto appearance = upload(l.appearance.data(), l.appearance.size() * sizeof(uint16_t));
            // The k = 2 table of s4 as one uint2 per atlas pixel: C_1(c) = c (Lefebvre & Hoppe 2005's
            // identity candidate) when c lies in its exemplar's interior, else none
            // (synth::kNoIdentityCandidate), and C_2(c) from PatchMatch.
            std::vector<cl_uint2> candidate_table(l.pixelCount());
            for (size_t c = 0; c < candidate_table.size(); ++c) {
                candidate_table[c].s[0] = synth::identityCandidate(l, static_cast<uint32_t>(c));
                candidate_table[c].s[1] = l.similar[c];
            }
            auto similar = upload(candidate_table.data(), candidate_table.size() * sizeof(cl_uint2));
            auto exemplar = upload(l.exemplar.data(), l.exemplar.size());
            auto rect_buffer = upload(rects.data(), rects.size() * sizeof(cl_int4));
            auto heights = upload(l.height_m.data(), l.height_m.size() * sizeof(float));
            const synth::SeedTable table = synth::seedTable(l);
            auto types = upload(l.type.data(), l.type.size());
            auto type_seeds = upload(table.seeds.data(), table.seeds.size() * sizeof(uint32_t));
            auto seed_ranges = upload(table.ranges.data(), table.ranges.size() * sizeof(int32_t));
            auto closed = upload(l.closed.data(), l.closed.size());
            const std::vector<uint8_t>& flags = levelGround(static_cast<int>(levels_.size()));
            auto level_ground = upload(flags.data(), flags.size());
            for (auto* r : {&appearance, &similar, &exemplar, &rect_buffer, &heights, &types, &type_seeds,
                            &seed_ranges, &closed, &level_ground})
                if (!*r) return r->status();
            d.types = std::move(types.value());
            d.type_seeds = std::move(type_seeds.value());
            d.seed_ranges = std::move(seed_ranges.value());
            d.appearance = std::move(appearance.value());
            d.candidates = std::move(similar.value());
            d.exemplar = std::move(exemplar.value());
            d.rects = std::move(rect_buffer.value());
            d.heights = std::move(heights.value());
            d.closed = std::move(closed.value());
            d.level_ground = std::move(level_ground.value());
            d.width = l.width;
            d.pixels = static_cast<cl_uint>(l.pixelCount());
            d.closed_pixels = static_cast<cl_uint>(l.closed.size());
            for (int m = 0; m < 4; ++m) d.offset.s[m] = l.appearance_offset[m], d.scale.s[m] = l.appearance_scale[m];
            levels_.push_back(std::move(d));
        }
        return Status::ok();
    }

    // Grows a buffer to hold `pixels` float4s (a state's pixels, or one int4 per patch cell); the
    // capacities are in bytes.
    Status reserve(BufferHandle& buffer, size_t& capacity, size_t pixels, const char* what = "state") {
        return cl::reserveBuffer(context_.get(), buffer, capacity, pixels * sizeof(cl_float4), what, host_memory_);
    }

    Status run(cl_kernel kernel, size_t width, size_t height) {
        const size_t global[2] = {cl::roundUp(width, local_[0]), cl::roundUp(height, local_[1])};
        TS_CL_CHECK(clEnqueueNDRangeKernel(queue_.get(), kernel, 2, nullptr, global, local_, 0, nullptr, nullptr));
        return Status::ok();
    }

    Status init(int level, const synth::LevelRegion& region, uint32_t seed) override {
        Status s = reserve(current_, current_capacity_, region.pixels());
        if (!s) return s;
        auto entry = synth::startingEntryLevels(*db_, level);
        if (!entry) return entry.status();
        entry_levels_ = std::move(entry.value());
        const synth::ShareLayout layout =
            synth::shareLayout(*db_, entry_levels_, level, region.x, region.y, region.width, region.height, seed);
        auto layout_buffer = upload(layout.exemplar.data(), layout.exemplar.size());
        if (!layout_buffer) return layout_buffer.status();
        layout_ = std::move(layout_buffer.value());
        coarsest_ = level;
        return patchLevel(level, region, seed, layout_.get(), layout.entering, false);
    }

    // Initial patches over current_ (synth/initial_patches.h): every pixel at the coarsest level, or
    // (admit_only) the pixels of exemplars entering at a finer one.
    Status patchLevel(int level, const synth::LevelRegion& region, uint32_t seed, cl_mem layout,
                      const std::vector<uint8_t>& entering_flags, bool admit_only) {
        const DeviceLevel& d = levels_[level];
        // The patch cells whose sites the region's pixels look at: their own and one around.
        using synth::floorDiv;
        const cl_int first_cx = floorDiv(region.x, kInitialPatchSize) - 1, first_cy = floorDiv(region.y, kInitialPatchSize) - 1;
        const cl_int grid_w = floorDiv(region.x + region.width - 1, kInitialPatchSize) + 1 - first_cx + 1;
        const cl_int grid_h = floorDiv(region.y + region.height - 1, kInitialPatchSize) + 1 - first_cy + 1;
        Status s = reserve(cells_, cells_capacity_, static_cast<size_t>(grid_w) * grid_h, "patch cells");
        if (!s) return s;
        const cl_uint salt = core::levelSalt(seed, level, 0);
        ArgSetter cell_args(init_cells_.get(), "init_cells");
        cell_args(cells_.get())(first_cx)(first_cy)(grid_w)(grid_h)(salt);
        if (!cell_args.status()) return cell_args.status();
        s = run(init_cells_.get(), grid_w, grid_h);
        if (!s) return s;
        auto entering = upload(entering_flags.data(), entering_flags.size());
        if (!entering) return entering.status();
        ArgSetter args(init_.get(), "init_level");
        args(current_.get())(toArg(region))(cells_.get())(first_cx)(first_cy)(grid_w)(layout)(d.rects.get())(
            entering.value().get())(cl_int{admit_only ? 1 : 0})(d.appearance.get())(d.width)(d.scale.s[0]);
        if (!args.status()) return args.status();
        return run(init_.get(), region.width, region.height);
    }

    Status upsample(int level, const synth::LevelRegion& parent, const synth::LevelRegion& child, float jitter,
                    uint32_t seed, const TypePaint* paint) override {
        Status s = reserve(next_, next_capacity_, child.pixels());
        if (!s) return s;
        const DeviceLevel& p = levels_[level + 1];
        const DeviceLevel& c = levels_[level];
        ArgSetter args(upsample_.get(), "upsample_jitter");
        args(current_.get())(toArg(parent))(next_.get())(toArg(child))(p.exemplar.get())(p.width)(p.rects.get())(
            c.rects.get())(jitter)(core::levelSalt(seed, level, 1))(core::levelSalt(seed, level, 2));
        if (!args.status()) return args.status();
        s = run(upsample_.get(), child.width, child.height);
        std::swap(current_, next_);
        std::swap(current_capacity_, next_capacity_);
        if (!s) return s;
        // Exemplars too small for the coarser levels enter here (synth/initial_patches.h).
        if (!synth::entersAt(entry_levels_, level)) return Status::ok();
        const synth::ShareLayout layout = synth::entryLayout(*db_, entry_levels_, level, child, seed, paint);
        auto layout_buffer = upload(layout.exemplar.data(), layout.exemplar.size());
        if (!layout_buffer) return layout_buffer.status();
        return patchLevel(level, child, seed, layout_buffer.value().get(), layout.entering, true);
    }

    Status beginLevel(int level, const synth::LevelRegion& region, const constraints::LevelConstraints& constraints,
                      const std::vector<uint8_t>& coherence, uint32_t seed) override {
        auto codes = upload(coherence.data(), coherence.size());
        if (!codes) return codes.status();
        coherence_ = std::move(codes.value());
        has_coherence_ = !coherence.empty();
        use_blend_ = constraints.blend.empty() ? 0 : 1;
        use_types_ = constraints.target_sets.empty() ? 0 : constraints.types_keep_only ? 2 : 1;
        seed_salt_ = synth::seedingSalt(seed, level);
        auto blend = upload(constraints.blend.data(), constraints.blend.size() * sizeof(float));
        if (!blend) return blend.status();
        blend_ = std::move(blend.value());
        auto targets = upload(constraints.target_sets.data(), constraints.target_sets.size() * sizeof(uint32_t));
        if (!targets) return targets.status();
        target_sets_ = std::move(targets.value());
        (void)region;
        return Status::ok();
    }

    Status beginPass(int, const synth::LevelRegion&, const synth::PassHistory& previous) override {
        use_prev_ = has_coherence_ && !previous.index.empty() ? 1 : 0;
        auto index = upload(previous.index.data(), previous.index.size() * sizeof(uint32_t));
        if (!index) return index.status();
        auto v = upload(previous.v.data(), previous.v.size() * sizeof(float));
        if (!v) return v.status();
        prev_index_ = std::move(index.value());
        prev_v_ = std::move(v.value());
        return Status::ok();
    }

    Status recordPass(int level, const synth::LevelRegion& region, SynthesisHistory::Pass& out) override {
        std::vector<cl_float4> state(region.pixels());
        TS_CL_CHECK(clEnqueueReadBuffer(queue_.get(), current_.get(), CL_TRUE, 0, state.size() * sizeof(cl_float4),
                                        state.data(), 0, nullptr, nullptr));
        const cl_uint width = static_cast<cl_uint>(levels_[level].width);
        out.index.resize(state.size());
        out.v.resize(state.size());
        for (size_t i = 0; i < state.size(); ++i) {
            out.index[i] = static_cast<uint32_t>(std::lround(state[i].s[1])) * width +
                           static_cast<uint32_t>(std::lround(state[i].s[0]));
            out.v[i] = state[i].s[2];
        }
        return Status::ok();
    }

    Status correct(int level, const synth::LevelRegion& region, int parity_x, int parity_y, int inset) override {
        const cl_int first_x = inset + ((parity_x - region.x - inset) & 1);
        const cl_int first_y = inset + ((parity_y - region.y - inset) & 1);
        if (region.width - inset <= first_x || region.height - inset <= first_y) return Status::ok();
        const size_t count_x = (region.width - inset - first_x + 1) / 2, count_y = (region.height - inset - first_y + 1) / 2;
        const DeviceLevel& d = levels_[level];
        ArgSetter args(correct_.get(), "correct");
        args(current_.get())(toArg(region))(first_x)(first_y)(cl_int(inset))(d.appearance.get())(d.candidates.get())(
            d.width)(d.scale)(target_sets_.get())(use_types_)(d.types.get())(
            d.type_seeds.get())(d.seed_ranges.get())(seed_salt_)(blend_.get())(use_blend_)(d.heights.get())(prev_index_.get())(
            prev_v_.get())(coherence_.get())(use_prev_)(d.exemplar.get())(layout_.get())(cl_int{level == coarsest_ ? 1 : 0})(
            d.level_ground.get())(synth::LevelGround::tolerance(*db_))(level_ground_.lowest(*db_, level))(
            cl_int{level < synth::kMedianOffsetLevels ? 1 : 0})(static_cast<cl_int>(d.pixels));
        if (!args.status()) return args.status();
        return run(correct_.get(), count_x, count_y);
    }

    // Runs `edit` on the level's state in place, mapped. On a CPU device (PoCL) the map is the
    // buffer's own memory: a read-back and a write-back cost two copies of the state (17 MB each
    // at level 0 of a 1024^2 synthesis); a GPU driver copies as they would.
    template <class Edit>
    Status editMappedState(const synth::LevelRegion& region, Edit&& edit) {
        static_assert(sizeof(synth::PixelState) == sizeof(cl_float4), "state layout");
        cl_int err = CL_SUCCESS;
        void* mapped = clEnqueueMapBuffer(queue_.get(), current_.get(), CL_TRUE, CL_MAP_READ | CL_MAP_WRITE, 0,
                                          region.pixels() * sizeof(cl_float4), 0, nullptr, nullptr, &err);
        TS_CL_CHECK_NAMED(err, "clEnqueueMapBuffer(state)");
        struct Unmap {  // also when `edit` throws: a buffer left mapped may not be used by a kernel
            cl_command_queue queue;
            cl_mem buffer;
            void* pointer;
            ~Unmap() {
                if (pointer) clEnqueueUnmapMemObject(queue, buffer, pointer, 0, nullptr, nullptr);
            }
        } unmap{queue_.get(), current_.get(), mapped};
        edit(static_cast<synth::PixelState*>(mapped));
        unmap.pointer = nullptr;
        TS_CL_CHECK(clEnqueueUnmapMemObject(queue_.get(), current_.get(), mapped, 0, nullptr, nullptr));
        return Status::ok();
    }

    // A preview level runs on the host (no kernel: it is as cheap there and the reference defines it).
    Status previewLevel(int level, const synth::LevelRegion& region, const std::vector<uint8_t>& coherence,
                        const synth::PassHistory& previous) override {
        return editMappedState(region, [&](synth::PixelState* state) {
            synth::referencePreviewLevel(db_->levels[level], region, coherence, previous, state);
        });
    }

    // The offset relaxation runs on the host, on the mapped state (offset_relaxation.h): a few
    // stencil iterations over one level, cheap beside its correction passes on CPU devices.
    Status relax(int level, const synth::LevelRegion& region, int iterations,
                 const synth::RelaxationInputs& inputs) override {
        const double spacing = db_->meters_per_pixel * std::ldexp(1.0, level);
        return editMappedState(region, [&](synth::PixelState* state) {
            synth::relaxOffsets(db_->levels[level], region, spacing, iterations, inputs, state);
        });
    }
    // Breaching (drainage_breach.h) runs on the device (cl/cl_drainage.h), on the state and the
    // level's coherence codes and constraint sums already there (beginLevel: the same arrays as
    // `inputs`): on a GPU the host's search took over 20 times the synthesis. On a CPU device
    // (PoCL) the C++ reference runs on the mapped state instead, the buffer's own memory there:
    // the same bits (cl_drainage_internal_test), in about half the kernels' time on 2 cores
    // (docs/benchmarks.md, "Drainage cost"). TERRASYNTH_CL_BREACH=device|host overrides the choice.
    float depthMargin(int level) override { return depth_margins_.at(*db_, level); }
    const std::vector<uint8_t>& basinExemplars() override { return depth_margins_.basinExemplars(*db_); }
    const std::vector<uint8_t>& levelGround(int level) override { return level_ground_.flags(*db_, level); }
    Status drain(int level, const synth::LevelRegion& region, int radius, const synth::DrainageInputs& inputs) override {
        if (!breach_on_device_)
            return editMappedState(region, [&](synth::PixelState* state) {
                synth::breachPits(db_->levels[level], region, radius, inputs, state, &breach_scratch_);
            });
        const DeviceLevel& d = levels_[level];
        const cl::DrainageLevelBuffers buffers{d.heights.get(), d.exemplar.get(), d.closed.get(), d.width, d.pixels,
                                               d.closed_pixels, d.level_ground.get()};
        cl::DeviceDrainageInputs on_device;
        on_device.coherence = has_coherence_ ? coherence_.get() : nullptr;
        on_device.blend = use_blend_ ? blend_.get() : nullptr;
        on_device.drained = inputs.drained;
        on_device.depth_margin = inputs.depth_margin;
        on_device.carve_to_edge = inputs.carve_to_edge;
        on_device.needed = inputs.needed;
        on_device.basin_exemplars = inputs.basin_exemplars;
        on_device.level_tolerance = inputs.level_tolerance;
        return breach_.run(queue_.get(), buffers, region, radius, on_device, current_.get());
    }

    Status resolve(int level, const synth::LevelRegion& region, const synth::LevelRegion& out, SynthesisOutput& output,
                   bool want_sources) override {
        const size_t pixels = out.pixels();
        // Kept between syntheses like the states (a fresh buffer per call was fresh pages per call).
        for (auto [buffer, capacity, bytes, what] :
             {std::tuple{&out_heights_, &out_heights_capacity_, pixels * sizeof(float), "heights"},
              std::tuple{&out_sources_, &out_sources_capacity_, want_sources ? pixels * 2 * sizeof(float) : 4, "sources"},
              std::tuple{&out_exemplars_, &out_exemplars_capacity_, want_sources ? pixels : 4, "source exemplars"}}) {
            Status reserved = cl::reserveBuffer(context_.get(), *buffer, *capacity, bytes, what, host_memory_);
            if (!reserved) return reserved;
        }
        cl_mem heights = out_heights_.get(), sources = out_sources_.get(), exemplars = out_exemplars_.get();
        const DeviceLevel& d = levels_[level];
        ArgSetter args(resolve_.get(), "resolve");
        args(current_.get())(toArg(region))(toArg(out))(d.heights.get())(d.exemplar.get())(d.rects.get())(d.width)(
            heights)(sources)(exemplars)(cl_int(want_sources ? 1 : 0));
        if (!args.status()) return args.status();
        Status s = run(resolve_.get(), out.width, out.height);
        if (!s) return s;
        TS_CL_CHECK(clEnqueueReadBuffer(queue_.get(), heights, CL_FALSE, 0, pixels * sizeof(float),
                                        output.heights.heights.data(), 0, nullptr, nullptr));
        std::vector<float> interleaved(want_sources ? pixels * 2 : 0);
        if (want_sources) {
            TS_CL_CHECK(clEnqueueReadBuffer(queue_.get(), sources, CL_FALSE, 0, pixels * 2 * sizeof(float),
                                            interleaved.data(), 0, nullptr, nullptr));
            TS_CL_CHECK(clEnqueueReadBuffer(queue_.get(), exemplars, CL_FALSE, 0, pixels,
                                            output.source_exemplar.data(), 0, nullptr, nullptr));
        }
        TS_CL_CHECK(clFinish(queue_.get()));
        for (size_t i = 0; i < interleaved.size() / 2; ++i) {
            output.source_x[i] = interleaved[2 * i];
            output.source_y[i] = interleaved[2 * i + 1];
        }
        return Status::ok();
    }

    cl::DeviceChoice device_;
    cl::ContextHandle context_;
    cl::QueueHandle queue_;
    cl::ProgramHandle program_;
    KernelHandle init_cells_, init_, upsample_, correct_, resolve_;
    std::vector<DeviceLevel> levels_;
    std::vector<int> entry_levels_;  // synth::entryLevels of the current synthesis
    int coarsest_ = -1;              // its coarsest level, whose passes hold layout_
    BufferHandle layout_;            // synth::shareLayout of the coarsest level's region
    BufferHandle current_, next_;
    BufferHandle cells_;  // init_cells' output (one int4 per patch cell), reused
    BufferHandle out_heights_, out_sources_, out_exemplars_;  // resolve's outputs, reused
    size_t out_heights_capacity_ = 0, out_sources_capacity_ = 0, out_exemplars_capacity_ = 0;
    BufferHandle placeholder_;
    BufferHandle blend_, target_sets_, prev_index_, prev_v_, coherence_;
    bool has_coherence_ = false;
    cl_int use_prev_ = 0;
    cl_int use_blend_ = 0, use_types_ = 0;
    cl_uint seed_salt_ = 0;
    size_t current_capacity_ = 0, next_capacity_ = 0, cells_capacity_ = 0;
    size_t local_[2] = {32, 2};
    synth::DepthMargins depth_margins_;
    synth::LevelGround level_ground_;
    cl::DeviceBreach breach_;
    bool breach_on_device_ = true;
    cl::HostMemory host_memory_;  // huge pages for large buffers on a CPU device
    synth::BreachScratch breach_scratch_;  // the host's breach (a CPU device)
    double bytes_per_pixel_ = 0.0;
};

}  // namespace

Result<std::unique_ptr<Synthesizer>> cl::createOpenClSynthesizer(std::shared_ptr<const ExemplarDatabase> db,
                                                                 const SynthesizerOptions& options) {
    auto synthesizer = std::make_unique<OpenClSynthesizer>(std::move(db));
    Status s = synthesizer->initialise(options);
    if (!s) return s;
    return std::unique_ptr<Synthesizer>(std::move(synthesizer));
}

}  // namespace terrasynth
