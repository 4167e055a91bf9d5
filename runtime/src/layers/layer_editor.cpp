// Interactive session: undoable edits over a LayerStack with cached layer pyramids.
// Undo keeps whole stack values (small: parameters only); contents come back from the cache or are
// rebuilt deterministically, so undo restores bit-identical heights either way.
#include <optional>

#include "layers/evaluator.h"
#include "layers/pyramid.h"
#include "terrasynth/layers.h"

namespace terrasynth {

namespace {
constexpr size_t kCacheBytes = size_t{768} << 20;
constexpr size_t kUndoDepth = 256;

Status badIndex(int index, size_t n) {
    return Status::error("layer index " + std::to_string(index) + " out of range (" + std::to_string(n) + " layers)");
}
}  // namespace

struct LayerEditor::Impl {
    LayerStack stack;
    layers::StackEvaluator evaluator;
    std::vector<LayerStack> undo, redo;
    Heightfield result;    // heights of `stack` when `current`; its storage is reused
    bool current = false;

    Impl(LayerStack s, Heightfield base) : stack(std::move(s)), evaluator(std::move(base)) {}

    // Applies one edit as an undo step; `edit` returns an error to leave everything unchanged.
    template <class Fn>
    Status edit(Fn&& fn) {
        LayerStack next = stack;
        if (Status s = fn(next); !s) return s;
        undo.push_back(std::move(stack));
        if (undo.size() > kUndoDepth) undo.erase(undo.begin());
        redo.clear();
        stack = std::move(next);
        current = false;
        return Status::ok();
    }
};

LayerEditor::LayerEditor(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
LayerEditor::LayerEditor(LayerEditor&&) noexcept = default;
LayerEditor& LayerEditor::operator=(LayerEditor&&) noexcept = default;
LayerEditor::~LayerEditor() = default;

Result<LayerEditor> LayerEditor::create(LayerStack stack, Heightfield base) {
    if (base.empty() || base.heights.size() != static_cast<size_t>(base.width) * base.height)
        return Status::error("layers: the base terrain is empty");
    if (Status s = validateBandSplit(stack.bands); !s) return s.withContext("layers[0].band_cuts_px");
    for (size_t i = 0; i < stack.layers.size(); ++i)
        if (Status s = validateEditLayer(stack.layers[i], "layers[" + std::to_string(i + 1) + "]"); !s) return s;
    return LayerEditor(std::make_unique<Impl>(std::move(stack), std::move(base)));
}

const LayerStack& LayerEditor::stack() const { return impl_->stack; }

Result<const Heightfield*> LayerEditor::currentHeights() {
    if (!impl_->current) {
        if (Status s = impl_->evaluator.evaluateInto(impl_->stack, impl_->result); !s) return s;
        impl_->current = true;
        impl_->evaluator.trim(kCacheBytes);
    }
    return &impl_->result;
}

Result<Heightfield> LayerEditor::heights() {
    auto h = currentHeights();
    if (!h) return h.status();
    return **h;
}

Result<BandDecomposition> LayerEditor::layerBands(int index) {
    const int n = static_cast<int>(impl_->stack.layers.size());
    if (index < -1 || index >= n) return badIndex(index, n);
    auto below = impl_->evaluator.plan(impl_->stack, index < 0 ? 0 : index);
    if (!below) return below.status();
    layers::Pyramid coeffs;
    const layers::Pyramid* mask = nullptr;
    std::shared_ptr<const layers::LayerContent> content;
    if (index < 0) {
        coeffs = *below->base;
    } else {
        LayerStack one = impl_->stack;
        one.layers[index].visible = true;
        auto with = impl_->evaluator.plan(one, index + 1);
        if (!with) return with.status();
        content = with->ops.back().content;
        coeffs = content->coeffs;
        if (content->kind != layers::OpKind::Add) mask = &content->mask;
    }
    const BandSplit split = impl_->stack.bands;
    auto band = [&](Band b) {
        layers::Pyramid p = coeffs;
        for (int l = 0; l <= p.depth(); ++l)
            if ((l == p.depth() ? Band::Low : split.bandOfLevel(l)) != b)
                std::fill(p.levels[l].samples.begin(), p.levels[l].samples.end(), 0.0f);
        layers::Plane plane = layers::collapse(p);
        if (mask)
            for (size_t i = 0; i < plane.samples.size(); ++i) plane.samples[i] *= mask->levels[0].samples[i];
        return layers::toField(std::move(plane), impl_->evaluator.grid());
    };
    return BandDecomposition{band(Band::Low), band(Band::Mid), band(Band::High)};
}

Status LayerEditor::addLayer(EditLayer layer, int index) {
    if (Status s = validateEditLayer(layer); !s) return s;
    return impl_->edit([&](LayerStack& s) {
        const int n = static_cast<int>(s.layers.size());
        if (index < -1 || index > n) return badIndex(index, n);
        s.layers.insert(s.layers.begin() + (index < 0 ? n : index), std::move(layer));
        return Status::ok();
    });
}

Status LayerEditor::removeLayer(int index) {
    return impl_->edit([&](LayerStack& s) {
        if (index < 0 || index >= static_cast<int>(s.layers.size())) return badIndex(index, s.layers.size());
        s.layers.erase(s.layers.begin() + index);
        return Status::ok();
    });
}

Status LayerEditor::moveLayer(int from, int to) {
    return impl_->edit([&](LayerStack& s) {
        const int n = static_cast<int>(s.layers.size());
        if (from < 0 || from >= n) return badIndex(from, n);
        if (to < 0 || to >= n) return badIndex(to, n);
        EditLayer moved = std::move(s.layers[from]);
        s.layers.erase(s.layers.begin() + from);
        s.layers.insert(s.layers.begin() + to, std::move(moved));
        return Status::ok();
    });
}

Status LayerEditor::setVisible(int index, bool visible) {
    return impl_->edit([&](LayerStack& s) {
        if (index < 0 || index >= static_cast<int>(s.layers.size())) return badIndex(index, s.layers.size());
        s.layers[index].visible = visible;
        return Status::ok();
    });
}

namespace {
Status checkWeights(const BandWeights& w) {
    for (float v : {w.low, w.mid, w.high})
        if (!(v >= 0.0f && v <= kMaxBandWeight)) return Status::error("weights: each band must be in [0, 4]");
    return Status::ok();
}
}  // namespace

Status LayerEditor::setWeights(int index, BandWeights weights) {
    if (Status s = checkWeights(weights); !s) return s;
    return impl_->edit([&](LayerStack& s) {
        if (index < 0 || index >= static_cast<int>(s.layers.size())) return badIndex(index, s.layers.size());
        s.layers[index].weights = weights;
        return Status::ok();
    });
}

Status LayerEditor::setBaseWeights(BandWeights weights) {
    if (Status s = checkWeights(weights); !s) return s;
    return impl_->edit([&](LayerStack& s) {
        s.base.weights = weights;
        return Status::ok();
    });
}

Status LayerEditor::replaceLayer(int index, EditLayer layer) {
    if (Status s = validateEditLayer(layer); !s) return s;
    return impl_->edit([&](LayerStack& s) {
        if (index < 0 || index >= static_cast<int>(s.layers.size())) return badIndex(index, s.layers.size());
        s.layers[index] = std::move(layer);
        return Status::ok();
    });
}

Status LayerEditor::setBase(BaseLayer base) {
    LayerStack probe = impl_->stack;
    probe.base = base;
    // Validate by planning only the base (reads files, checks fractal parameters).
    if (auto p = impl_->evaluator.plan(probe, 0); !p) return p.status();
    return impl_->edit([&](LayerStack& s) {
        s.base = std::move(base);
        return Status::ok();
    });
}

Status LayerEditor::setBandSplit(BandSplit split) {
    if (Status s = validateBandSplit(split); !s) return s;
    return impl_->edit([&](LayerStack& s) {
        s.bands = split;
        return Status::ok();
    });
}

Status LayerEditor::setStack(LayerStack stack) {
    if (Status s = validateBandSplit(stack.bands); !s) return s.withContext("layers[0].band_cuts_px");
    for (size_t i = 0; i < stack.layers.size(); ++i)
        if (Status s = validateEditLayer(stack.layers[i], "layers[" + std::to_string(i + 1) + "]"); !s) return s;
    return impl_->edit([&](LayerStack& s) {
        s = std::move(stack);
        return Status::ok();
    });
}

Status LayerEditor::setSynthesizedTerrain(Heightfield terrain) {
    const Heightfield& grid = impl_->evaluator.grid();
    if (terrain.width != grid.width || terrain.height != grid.height ||
        terrain.heights.size() != static_cast<size_t>(terrain.width) * terrain.height)
        return Status::error("layers: the synthesized terrain must keep the grid size " + std::to_string(grid.width) +
                             "x" + std::to_string(grid.height));
    impl_->evaluator.setSynthesized(std::move(terrain));
    impl_->current = false;
    return Status::ok();
}

Status LayerEditor::mergeDown(int index) {
    return impl_->edit([&](LayerStack& s) {
        const int n = static_cast<int>(s.layers.size());
        if (index < 1 || index >= n) return Status::error("mergeDown: layer " + std::to_string(index) +
                                                          " has no edit layer below it (" + std::to_string(n) + " layers)");
        EditLayer merged;
        merged.name = s.layers[index - 1].name + " + " + s.layers[index].name;
        GroupParams group;
        group.children = {s.layers[index - 1], s.layers[index]};
        merged.tool = std::move(group);
        s.layers.erase(s.layers.begin() + index);
        s.layers[index - 1] = std::move(merged);
        return Status::ok();
    });
}

Result<std::vector<Heightfield>> LayerEditor::holeFillPreviews(int index, int generation) {
    const int n = static_cast<int>(impl_->stack.layers.size());
    if (index < 0 || index >= n) return badIndex(index, n);
    const auto* p = std::get_if<HoleFillParams>(&impl_->stack.layers[index].tool);
    if (!p) return Status::error("layer " + std::to_string(index) + " is not a hole_fill layer");
    if (generation < 0 || generation > static_cast<int>(p->choices.size()))
        return Status::error("generation must be in 0.." + std::to_string(p->choices.size()));
    auto below = impl_->evaluator.evaluate(impl_->stack, index);
    if (!below) return below.status();
    if (Status s = checkHoleFillCost(*p, below->width, below->height, generation + 1); !s) return s;
    std::optional<Heightfield> chosen;
    for (int g = 0; g < generation; ++g) {
        auto v = holeFillVariants(*below, *p, g, chosen ? &*chosen : nullptr);
        if (!v) return v.status();
        chosen = std::move((*v)[p->choices[g]]);
    }
    return holeFillVariants(*below, *p, generation, chosen ? &*chosen : nullptr);
}

bool LayerEditor::canUndo() const { return !impl_->undo.empty(); }
bool LayerEditor::canRedo() const { return !impl_->redo.empty(); }

bool LayerEditor::undo() {
    if (impl_->undo.empty()) return false;
    impl_->redo.push_back(std::move(impl_->stack));
    impl_->stack = std::move(impl_->undo.back());
    impl_->undo.pop_back();
    impl_->current = false;
    return true;
}

bool LayerEditor::redo() {
    if (impl_->redo.empty()) return false;
    impl_->undo.push_back(std::move(impl_->stack));
    impl_->stack = std::move(impl_->redo.back());
    impl_->redo.pop_back();
    impl_->current = false;
    return true;
}

}  // namespace terrasynth
