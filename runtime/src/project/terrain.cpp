// Terrain: a project ready for height queries. Synthesis is a pure function of the global pixel
// (windowed). Edits that need the whole extent (freeze and pastes, s5.3; the layer stack of Bradbury
// et al. 2014) act inside the project's extent as a cached height *difference*:
// window = synthesis(window) + edit(window), where the edit is zero outside the extent and
// box-averaged for coarser levels, so tiles stay seamless at every level.
#include "terrasynth/terrain.h"

#include <cmath>

#include "terrasynth/incremental.h"
#include "terrasynth/layers.h"

namespace terrasynth {

Result<std::shared_ptr<Terrain>> Terrain::open(const std::string& project_path, const TerrainOptions& options) {
    auto project = loadProject(project_path);
    if (!project) return project.status();
    return fromProject(std::move(project.value()), options);
}

Result<std::shared_ptr<Terrain>> Terrain::fromProject(Project project, const TerrainOptions& options) {
    if (Status s = checkProjectExtent(project); !s) return s.withContext(project.path);
    if (project.hasLayers()) {
        auto stack = parseLayerStack(project.layers_json, project.folder());
        if (!stack) return stack.status().withContext(project.path);
    }
    auto db = openProjectDatabase(project, options.database);
    if (!db) return db.status();
    auto constraints = parseConstraints(project.constraints_json, project.folder(), *db.value(), project.origin_x, project.origin_y,
                                        project.width, project.height);
    if (!constraints) return constraints.status().withContext(project.path);
    if (!constraints->empty())
        project.synthesis.constraints = std::make_shared<const SynthesisConstraints>(std::move(constraints.value()));
    std::shared_ptr<Terrain> terrain(new Terrain(std::move(project), db.value(), options));
    // Fail early (missing OpenCL device, kernel build) rather than on the first tile.
    auto synthesizer = terrain->synthesizerForThisThread();
    if (!synthesizer) return synthesizer.status();
    // Lifted once here, so every window and tile synthesizes with the same targets.
    SynthesisParams& params = terrain->project_.synthesis;
    if (terrain->project_.hold_point_heights && params.constraints && !params.constraints->points.empty()) {
        auto lifted = liftPointConstraints(*synthesizer.value(), params);
        if (!lifted) return lifted.status().withContext(terrain->project_.path + ": constraints.points");
        params.constraints = std::move(lifted.value());
    }
    return terrain;
}

double Terrain::metersPerPixel(int level) const { return db_->meters_per_pixel * std::ldexp(1.0, level); }

Result<Synthesizer*> Terrain::synthesizerForThisThread() {
    std::lock_guard<std::mutex> lock(mutex_);
    auto& slot = synthesizers_[std::this_thread::get_id()];
    if (!slot) {
        auto created = Synthesizer::create(db_, options_.synthesizer);
        if (!created) return created.status();
        slot = std::move(created.value());
    }
    return slot.get();
}

bool Terrain::hasExtentEdit() const {
    const auto& c = project_.synthesis.constraints;
    return project_.hasLayers() || (c && (!c->freeze.empty() || !c->pastes.empty()));
}

// The extent as the user shaped it: synthesis with constraints, then (s5.3) the freeze brush and
// pastes through coherent re-synthesis, then the layer stack.
Result<Heightfield> Terrain::shapedExtent(Synthesizer& synthesizer) {
    const auto& c = project_.synthesis.constraints;
    if (!c || (c->freeze.empty() && c->pastes.empty())) {
        auto out = synthesizer.synthesize(extent(), project_.synthesis, 0, false);
        if (!out) return out.status();
        return std::move(out->heights);
    }
    // Frozen pixels keep the terrain the seed alone makes; constraints act everywhere else.
    SynthesisParams plain = project_.synthesis;
    plain.constraints.reset();
    auto incremental = IncrementalTerrain::create(synthesizer, extent(), plain);
    if (!incremental) return incremental.status();
    incremental->holdPointHeights(project_.hold_point_heights);
    incremental->freeze(c->freeze);
    if (c->shapesTerrain()) {
        auto shaping = std::make_shared<SynthesisConstraints>(*c);
        shaping->freeze = TypePaint();
        shaping->pastes.clear();
        Status s = incremental->update(shaping, extent());
        if (!s) return s;
    }
    for (size_t i = 0; i < c->pastes.size(); ++i) {
        Status s = incremental->paste(c->pastes[i]);
        if (!s) return s.withContext(project_.path + ": constraints.pastes[" + std::to_string(i) + "]");
    }
    return incremental->heights();
}

Result<const std::vector<float>*> Terrain::extentEdit() {
    std::lock_guard<std::mutex> lock(edit_mutex_);
    if (edit_ready_) return &edit_;
    auto synthesizer = synthesizerForThisThread();
    if (!synthesizer) return synthesizer.status();
    auto shaped = shapedExtent(*synthesizer.value());
    if (!shaped) return shaped.status();
    if (project_.hasLayers()) {
        auto stack = parseLayerStack(project_.layers_json, project_.folder());
        if (!stack) return stack.status().withContext(project_.path);
        auto layered = applyLayerStack(stack.value(), shaped.value());
        if (!layered) return layered.status().withContext(project_.path);
        if (layered->width != shaped->width || layered->height != shaped->height)
            return Status::error(project_.path + ": layer stack changed the terrain size");
        shaped = std::move(layered.value());
    }
    auto plain = synthesizer.value()->synthesize(extent(), project_.synthesis, 0, false);
    if (!plain) return plain.status();
    edit_.resize(plain->heights.size());
    for (size_t i = 0; i < edit_.size(); ++i) edit_[i] = shaped->heights[i] - plain->heights.heights[i];
    shaped_ = std::move(shaped->heights);
    edit_ready_ = true;
    return &edit_;
}

Result<SynthesisOutput> Terrain::synthesize(const PixelWindow& window, int level, bool want_sources) {
    auto synthesizer = synthesizerForThisThread();
    if (!synthesizer) return synthesizer.status();
    auto out = synthesizer.value()->synthesize(window, project_.synthesis, level, want_sources);
    if (!out || !hasExtentEdit()) return out;
    auto edit = extentEdit();
    if (!edit) return edit.status();
    const PixelWindow e = extent();
    Heightfield& h = out->heights;
    if (level == 0) {
        // The shaped heights themselves: plain + (shaped - plain) can be an ulp off, and frozen and
        // pasted pixels must stay bit-identical.
        for (int y = 0; y < h.height; ++y)
            for (int x = 0; x < h.width; ++x) {
                const int64_t gx = window.x + x - e.x, gy = window.y + y - e.y;
                if (gx >= 0 && gy >= 0 && gx < e.width && gy < e.height)
                    h.at(x, y) = shaped_[static_cast<size_t>(gy) * e.width + gx];
            }
        return out;
    }
    // Coarser levels add the edit, box-averaged over the 2^level x 2^level block of extent pixels of
    // each sample.
    const int64_t block = int64_t(1) << level;
    for (int y = 0; y < h.height; ++y) {
        for (int x = 0; x < h.width; ++x) {
            const int64_t gx0 = (window.x + x) * block - e.x, gy0 = (window.y + y) * block - e.y;
            if (gx0 + block <= 0 || gy0 + block <= 0 || gx0 >= e.width || gy0 >= e.height) continue;
            double sum = 0.0;
            for (int64_t by = std::max<int64_t>(0, gy0); by < std::min<int64_t>(e.height, gy0 + block); ++by)
                for (int64_t bx = std::max<int64_t>(0, gx0); bx < std::min<int64_t>(e.width, gx0 + block); ++bx)
                    sum += (*edit.value())[static_cast<size_t>(by) * e.width + bx];
            h.at(x, y) += static_cast<float>(sum / static_cast<double>(block * block));
        }
    }
    return out;
}

Result<Heightfield> Terrain::heights(const PixelWindow& window, int level) {
    auto out = synthesize(window, level, false);
    if (!out) return out.status();
    return std::move(out->heights);
}

}  // namespace terrasynth
