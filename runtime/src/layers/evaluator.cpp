#include "layers/evaluator.h"

#include <algorithm>
#include <cstring>
#include <vector>

#include "layers/layer_content.h"
#include "layers/layer_json.h"
#include "layers/random.h"

namespace terrasynth::layers {
namespace {

uint64_t mixIn(uint64_t h, uint64_t v) { return mix64(h ^ mix64(v + 0x632BE59BD9B4E019ull)); }
uint64_t weightBits(const BandWeights& w) {
    uint32_t a, b, c;
    std::memcpy(&a, &w.low, 4), std::memcpy(&b, &w.mid, 4), std::memcpy(&c, &w.high, 4);
    return mixIn(mixIn(a, b), c);
}

}  // namespace

StackEvaluator::StackEvaluator(Heightfield synthesized) { setSynthesized(std::move(synthesized)); }

void StackEvaluator::setSynthesized(Heightfield synthesized) {
    TERRASYNTH_REQUIRE(synthesized_.empty() || (synthesized.width == synthesized_.width &&
                                                synthesized.height == synthesized_.height),
                       "the synthesized base keeps its grid");
    synthesized_ = std::move(synthesized);
    std::string bytes(reinterpret_cast<const char*>(synthesized_.heights.data()),
                      synthesized_.heights.size() * sizeof(float));
    synthesized_print_ = mixIn(fingerprint(bytes), (static_cast<uint64_t>(synthesized_.width) << 32) ^ synthesized_.height);
}

Result<CompositionPlan> StackEvaluator::plan(const LayerStack& stack, int upto) {
    TERRASYNTH_REQUIRE(!synthesized_.empty(), "the grid must not be empty");
    if (Status s = validateBandSplit(stack.bands); !s) return s.withContext("layers[0].band_cuts_px");
    ++tick_;
    CompositionPlan plan;
    plan.split = stack.bands;
    plan.base_weights = stack.base.weights;
    BaseLayer unweighted = stack.base;
    unweighted.weights = BandWeights{};
    uint64_t base_key = mixIn(fingerprint(baseToJson(unweighted, stack.bands).dump()), synthesized_print_);
    if (stack.base.source == BaseSource::Heightmap) base_key = mixIn(base_key, fingerprint(stack.base_dir));
    auto it = bases_.find(base_key);
    if (it == bases_.end()) {
        auto heights = baseHeights(stack.base, synthesized_, stack.base_dir);
        if (!heights) return Status::error("layers[0]." + heights.message());
        auto pyr = std::make_shared<Pyramid>(buildLaplacian(toPlane(*heights), stack.bands.depth()));
        bases_.clear();  // one base at a time: it is as large as all layers' level 0
        it = bases_.emplace(base_key, std::move(pyr)).first;
    }
    plan.base = it->second;
    uint64_t below_print = mixIn(base_key, weightBits(stack.base.weights));
    const int n = upto < 0 ? static_cast<int>(stack.layers.size()) : std::min<int>(upto, stack.layers.size());
    // Element 0 of the JSON array is the base, so edit layer i is layers[i + 1] there.
    for (int i = 0; i < n; ++i)
        if (Status s = append(stack.layers[i], "layers[" + std::to_string(i + 1) + "]", stack, plan, below_print); !s)
            return s;
    return plan;
}

Status StackEvaluator::append(const EditLayer& layer, const std::string& where, const LayerStack& stack,
                              CompositionPlan& plan, uint64_t& below_print) {
    if (!layer.visible) return Status::ok();
    uint64_t key = fingerprint(toolToJson(layer.tool).dump());
    key = mixIn(key, (static_cast<uint64_t>(stack.bands.high_mid_cut_px) << 16) ^ stack.bands.mid_low_cut_px);
    key = mixIn(key, synthesized_print_);
    if (readsBelow(layer.tool)) key = mixIn(key, below_print);
    if (std::holds_alternative<PasteParams>(layer.tool)) key = mixIn(key, fingerprint(stack.base_dir));
    auto found = cache_.find(key);
    std::shared_ptr<const LayerContent> content;
    if (found != cache_.end()) {
        content = found->second.content;
    } else {
        auto built = build(layer, where, stack, plan, below_print);
        if (!built) return built.status();
        content = *built;
    }
    cache_[key] = Entry{content, tick_};
    plan.ops.push_back({content, layer.weights});
    below_print = mixIn(mixIn(below_print, key), weightBits(layer.weights));
    return Status::ok();
}

Result<std::shared_ptr<const LayerContent>> StackEvaluator::build(const EditLayer& layer, const std::string& where,
                                                                  const LayerStack& stack, const CompositionPlan& below,
                                                                  uint64_t below_print) {
    auto named = [&](const Status& s) { return Status::error(where + "." + s.message()); };
    if (!readsBelow(layer.tool)) {
        auto relief = toolRelief(layer.tool, synthesized_);
        if (!relief) return named(relief.status());
        return std::shared_ptr<const LayerContent>(additiveContent(*relief, stack.bands));
    }
    if (auto* group = std::get_if<GroupParams>(&layer.tool)) {
        // The group's content is the change its children make to the combined pyramid below.
        CompositionPlan inner = below;
        uint64_t inner_print = below_print;
        for (size_t k = 0; k < group->children.size(); ++k)
            if (Status s = append(group->children[k], where + ".layers[" + std::to_string(k) + "]", stack, inner,
                                  inner_print);
                !s)
                return s;
        auto content = std::make_shared<LayerContent>();
        content->kind = OpKind::Add;
        content->coeffs = compositor_.combine(inner);
        const Pyramid before = compositor_.combine(below);
        for (size_t l = 0; l < before.levels.size(); ++l) {
            std::vector<float>& a = content->coeffs.levels[l].samples;
            const std::vector<float>& b = before.levels[l].samples;
            for (size_t i = 0; i < a.size(); ++i) a[i] -= b[i];
        }
        computeSupport(*content);
        return std::shared_ptr<const LayerContent>(content);
    }
    const Heightfield terrain = compose(below);
    Result<std::shared_ptr<LayerContent>> built =
        std::holds_alternative<PasteParams>(layer.tool)
            ? pasteContent(std::get<PasteParams>(layer.tool), terrain, stack.bands, stack.base_dir)
            : holeFillContent(std::get<HoleFillParams>(layer.tool), terrain, stack.bands);
    if (!built) return named(built.status());
    return std::shared_ptr<const LayerContent>(*built);
}

Heightfield StackEvaluator::compose(const CompositionPlan& plan) {
    Plane out;
    compositor_.compose(plan, out);
    return toField(std::move(out), synthesized_);
}

Result<Heightfield> StackEvaluator::evaluate(const LayerStack& stack, int upto) {
    auto p = plan(stack, upto);
    if (!p) return p.status();
    // Nothing to blend: hand the synthesized terrain back bit for bit (no pyramid round trip).
    if (p->ops.empty() && stack.base.source == BaseSource::Synthesized && p->base_weights == BandWeights{})
        return synthesized_;
    return compose(*p);
}

Status StackEvaluator::evaluateInto(const LayerStack& stack, Heightfield& out) {
    auto p = plan(stack);
    if (!p) return p.status();
    if (p->ops.empty() && stack.base.source == BaseSource::Synthesized && p->base_weights == BandWeights{}) {
        out = synthesized_;
        return Status::ok();
    }
    Plane plane;
    plane.width = out.width;
    plane.height = out.height;
    plane.samples = std::move(out.heights);
    compositor_.compose(*p, plane);
    out = toField(std::move(plane), synthesized_);
    return Status::ok();
}

void StackEvaluator::trim(size_t max_bytes) {
    size_t total = 0;
    std::vector<std::pair<uint64_t, uint64_t>> order;  // (last_used, key)
    for (auto& [key, e] : cache_) {
        total += e.content->bytes();
        order.push_back({e.last_used, key});
    }
    std::sort(order.begin(), order.end());
    for (auto& [used, key] : order) {
        if (total <= max_bytes || used == tick_) break;
        total -= cache_[key].content->bytes();
        cache_.erase(key);
    }
}

}  // namespace terrasynth::layers
