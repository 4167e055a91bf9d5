// Plans and evaluates a LayerStack on one grid, caching every layer's pyramid content.
//
// Cache keys: a layer's content depends on its tool parameters, the band split and the grid; layers
// that read the terrain below (paste, hole fill, group) also depend on a fingerprint of everything
// below them (base, visible layers, their weights). Weights of a layer never enter its own key, so
// a weight change reuses all contents except those of terrain-reading layers above it.
#pragma once

#include <memory>
#include <string>
#include <unordered_map>

#include "layers/compositor.h"
#include "terrasynth/layers.h"

namespace terrasynth::layers {

class StackEvaluator {
public:
    // `synthesized` is the base for BaseSource::Synthesized and fixes the grid size and spacing.
    explicit StackEvaluator(Heightfield synthesized);

    const Heightfield& grid() const { return synthesized_; }
    // Replaces the synthesized base (same size and spacing). Contents that do not read the terrain
    // below stay cached; those that do are keyed by it and rebuilt on demand.
    void setSynthesized(Heightfield synthesized);
    // The plan for the visible layers among stack.layers[0, upto) (upto < 0: all of them).
    Result<CompositionPlan> plan(const LayerStack& stack, int upto = -1);
    Heightfield compose(const CompositionPlan& plan);
    Result<Heightfield> evaluate(const LayerStack& stack, int upto = -1);
    // Same, composing into `out` and reusing its storage (no allocation once sized).
    Status evaluateInto(const LayerStack& stack, Heightfield& out);
    // Drops least recently used contents not in the last plan until the cache is under max_bytes.
    void trim(size_t max_bytes);

private:
    struct Entry {
        std::shared_ptr<const LayerContent> content;
        uint64_t last_used = 0;
    };
    Status append(const EditLayer& layer, const std::string& where, const LayerStack& stack, CompositionPlan& plan,
                  uint64_t& below_print);
    Result<std::shared_ptr<const LayerContent>> build(const EditLayer& layer, const std::string& where,
                                                      const LayerStack& stack, const CompositionPlan& below,
                                                      uint64_t below_print);

    Heightfield synthesized_;
    uint64_t synthesized_print_ = 0;
    std::unordered_map<uint64_t, Entry> cache_;
    std::unordered_map<uint64_t, std::shared_ptr<const Pyramid>> bases_;
    Compositor compositor_;
    uint64_t tick_ = 0;
};

}  // namespace terrasynth::layers
