// The layers panel (Bradbury et al. 2014): the stack, three band sliders per layer and for the base
// (s3.2), each layer's parameters, and the hole-fill previews (s4.4: three variants, pick one).
#include <cmath>

#include "editor_app.h"
#include "thumbnails.h"

namespace terrasynth::editor {
namespace {
constexpr float kRightWidth = 310.0f, kStatusHeight = 26.0f;
constexpr ImGuiWindowFlags kPanelFlags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse;
}  // namespace

void EditorApp::drawBandSliders(const std::string& id, BandWeights weights, int layer_index) {
    // One request per change while dragging (latest wins), one undo step per drag.
    float* bands[3] = {&weights.low, &weights.mid, &weights.high};
    const char* names[3] = {"low", "mid", "high"};
    bool changed = false;
    for (int b = 0; b < 3; ++b) {
        const std::string key = id + "." + names[b];
        float& live = liveValue(key, *bands[b]);
        changed |= ImGui::SliderFloat(names[b], &live, 0.0f, kMaxBandWeight, "%.2f");
        trackGesture(key);
        noteItem(key);
        *bands[b] = live;
    }
    if (!changed) return;
    if (layer_index < 0)
        submitDragStep(InputKind::BandSlider, "base bands", "weights:" + id,
                       [weights](EditSession& s) { return s.setBaseWeights(weights); });
    else
        submitDragStep(InputKind::BandSlider, "layer bands", "weights:" + id,
                       [layer_index, weights](EditSession& s) { return s.setLayerWeights(layer_index, weights); });
}

void EditorApp::drawLayersPanel() {
    const float top = ImGui::GetFrameHeight();
    const float h = 0.55f * (host_.height() - top - kStatusHeight);
    ImGui::SetNextWindowPos(ImVec2(host_.width() - kRightWidth, top), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(kRightWidth, h), ImGuiCond_Always);
    ImGui::Begin("Layers", nullptr, kPanelFlags);
    const LayerStack& stack = view_->layers;
    ImGui::TextDisabled("Base: %s", stack.base.source == BaseSource::Synthesized ? "synthesized terrain" : "other");
    ImGui::PushID("base");
    drawBandSliders("base", stack.base.weights, -1);
    ImGui::PopID();
    ImGui::Separator();
    const int n = static_cast<int>(stack.layers.size());
    if (n == 0) ImGui::TextDisabled("No layers: use the layer tools (peak, ridge, ...)");
    // Top of the stack first, as in image editors.
    for (int i = n - 1; i >= 0; --i) {
        const EditLayer& layer = stack.layers[static_cast<size_t>(i)];
        ImGui::PushID(i);
        const std::string item = "layer." + std::to_string(i);
        bool visible = layer.visible;
        if (ImGui::Checkbox("##visible", &visible)) {
            EditRequest r;
            r.label = visible ? "show layer" : "hide layer";
            r.run = [i, visible](EditSession& s) { return s.setLayerVisible(i, visible); };
            submit(std::move(r));
        }
        noteItem(item + ".visible");
        ImGui::SameLine();
        const std::string label = std::to_string(i) + ": " + layer.name + " (" + toolTypeName(layer.tool) + ")";
        if (ImGui::Selectable(label.c_str(), selection_.layer == i, 0, ImVec2(150, 0))) selection_.layer = i;
        noteItem(item);
        ImGui::SameLine();
        auto button = [&](const char* text, const char* id, bool enabled, const char* what,
                          std::function<Result<PixelWindow>(EditSession&)> run) {
            if (!enabled) ImGui::BeginDisabled();
            if (ImGui::SmallButton(text)) {
                EditRequest r;
                r.label = what;
                r.run = std::move(run);
                submit(std::move(r));
            }
            noteItem(item + "." + id);
            if (!enabled) ImGui::EndDisabled();
        };
        button("^", "up", i + 1 < n, "move layer up", [i](EditSession& s) { return s.moveLayer(i, i + 1); });
        ImGui::SameLine();
        button("v", "down", i > 0, "move layer down", [i](EditSession& s) { return s.moveLayer(i, i - 1); });
        ImGui::SameLine();
        button("merge", "merge", i > 0, "merge layer down", [i](EditSession& s) { return s.mergeLayerDown(i); });
        ImGui::SameLine();
        button("x", "remove", true, "remove layer", [i](EditSession& s) { return s.removeLayer(i); });
        if (ImGui::IsItemClicked() && selection_.layer == i) selection_.layer = -1;
        ImGui::PopID();
    }
    if (selection_.layer >= 0 && selection_.layer < n) {
        ImGui::Separator();
        ImGui::Text("Layer %d bands", selection_.layer);
        ImGui::PushID(1000 + selection_.layer);
        drawBandSliders("layer" + std::to_string(selection_.layer), stack.layers[static_cast<size_t>(selection_.layer)].weights,
                        selection_.layer);
        drawLayerParams(selection_.layer, stack.layers[static_cast<size_t>(selection_.layer)]);
        ImGui::PopID();
    }
    ImGui::End();
}

void EditorApp::drawLayerParams(int index, const EditLayer& layer) {
    EditLayer next = layer;
    bool changed = false;
    const std::string k = "params." + std::to_string(index) + ".";
    auto field = [&](const char* label, const char* key, double* value, float speed, float lo, float hi, const char* fmt) {
        float& live = liveValue(k + key, static_cast<float>(*value));
        changed |= ImGui::DragFloat(label, &live, speed, lo, hi, fmt);
        trackGesture(k + key);
        *value = live;
    };
    if (auto* peak = std::get_if<PeakParams>(&next.tool)) {
        field("height (m)", "height", &peak->height_m, 10.0f, -5000.0f, 5000.0f, "%.0f");
        field("spread (px)", "spread", &peak->spread_px, 0.5f, 1.0f, 500.0f, "%.0f");
        field("skewness", "skew", &peak->skewness, 0.01f, -0.85f, 0.85f, "%.2f");
        field("kurtosis", "kurt", &peak->kurtosis, 0.02f, -1.0f, 5.0f, "%.2f");
        field("skew azimuth", "azimuth", &peak->skew_azimuth_deg, 1.0f, 0.0f, 360.0f, "%.0f");
    } else if (auto* ridge = std::get_if<RidgeParams>(&next.tool)) {
        if (!ridge->profile_m.empty()) field("crest (m)", "crest", &ridge->profile_m[0], 5.0f, -5000.0f, 5000.0f, "%.0f");
        field("width (px)", "width", &ridge->width_px, 0.5f, 1.0f, 200.0f, "%.0f");
    } else if (auto* noise = std::get_if<NoiseParams>(&next.tool)) {
        field("amplitude (m)", "amp", &noise->fractal.amplitude_m, 1.0f, 0.0f, 3000.0f, "%.0f");
        field("wavelength (px)", "wave", &noise->fractal.wavelength_px, 1.0f, 2.0f, 2048.0f, "%.0f");
    } else if (auto* paste = std::get_if<PasteParams>(&next.tool)) {
        field("vertical scale", "vscale", &paste->vertical_scale, 0.01f, 0.01f, 10.0f, "%.2f");
        bool replace = paste->blend == PasteBlend::Replace;
        if (ImGui::Checkbox("replace (else max gradient)", &replace)) {
            paste->blend = replace ? PasteBlend::Replace : PasteBlend::MaxGradient;
            changed = true;
        }
    } else if (auto* fill = std::get_if<HoleFillParams>(&next.tool)) {
        ImGui::Text("%zu pick(s): ", fill->choices.size());
        ImGui::SameLine();
        if (ImGui::SmallButton("previews")) {
            previews_layer_ = index;
            previews_generation_ = static_cast<int>(fill->choices.size()) - 1;
            releasePreviewImages();
        }
        noteItem("holefill.previews");
    } else if (const auto* sketch = std::get_if<PerspectiveParams>(&next.tool)) {
        ImGui::Text("%zu silhouette stroke(s) over %s", sketch->strokes.size(), sketch->reference_image.c_str());
    }
    if (!changed) return;
    EditRequest r;
    r.label = "set layer";
    r.coalesce_key = "layer-params";
    r.run = [index, next](EditSession& s) { return s.replaceLayer(index, next); };
    submit(std::move(r));
}

void EditorApp::drawHoleFillPreviews() {
    if (previews_layer_ < 0) return;
    const LayerStack& stack = view_->layers;
    if (previews_layer_ >= static_cast<int>(stack.layers.size())) {
        if (worker_->idle()) previews_layer_ = -1;  // the layer went away (undo), or is not there yet
        return;
    }
    const auto* fill = std::get_if<HoleFillParams>(&stack.layers[static_cast<size_t>(previews_layer_)].tool);
    if (!fill) {
        previews_layer_ = -1;
        return;
    }
    if (preview_images_.empty() && !previews_pending_) {
        previews_pending_ = true;
        const int index = previews_layer_, generation = previews_generation_;
        auto pictures = std::make_shared<std::vector<Picture>>();
        EditRequest r;
        r.label = "hole fill previews";
        r.run = [index, generation, pictures](EditSession& s) -> Result<PixelWindow> {
            auto variants = s.holeFillPreviews(index, generation);
            if (!variants) return variants.status();
            for (const Heightfield& v : *variants) pictures->push_back(hillshadePicture(v, 160));
            return PixelWindow{};
        };
        r.done = [this, pictures](const EditResult& res) {
            previews_pending_ = false;
            if (!res.status) {
                previews_layer_ = -1;
                return;
            }
            for (const Picture& p : *pictures) preview_images_.push_back(host_.uploadImage(p.rgba, p.width, p.height));
        };
        submit(std::move(r));
    }
    ImGui::SetNextWindowPos(ImVec2(0.5f * host_.width(), host_.height() - kStatusHeight - 8.0f), ImGuiCond_Always, ImVec2(0.5f, 1.0f));
    ImGui::Begin("Hole fill: pick a variant", nullptr, kPanelFlags | ImGuiWindowFlags_AlwaysAutoResize);
    ImGui::Text("Layer %d, generation %d", previews_layer_, previews_generation_);
    if (preview_images_.empty()) {
        ImGui::TextDisabled("quilting three variants...");
    } else {
        for (size_t k = 0; k < preview_images_.size(); ++k) {
            if (k) ImGui::SameLine();
            ImGui::BeginGroup();
            ImGui::Image(preview_images_[k], ImVec2(160, 160 * view_->extent.height / float(view_->extent.width)));
            const bool picked = previews_generation_ < static_cast<int>(fill->choices.size()) &&
                                fill->choices[static_cast<size_t>(previews_generation_)] == static_cast<int>(k);
            if (ImGui::RadioButton(("variant " + std::to_string(k + 1)).c_str(), picked)) {
                HoleFillParams next = *fill;
                next.choices.resize(static_cast<size_t>(previews_generation_));
                next.choices.push_back(static_cast<int>(k));
                EditLayer layer = stack.layers[static_cast<size_t>(previews_layer_)];
                layer.tool = next;
                const int index = previews_layer_;
                EditRequest r;
                r.label = "pick hole fill";
                r.run = [index, layer](EditSession& s) { return s.replaceLayer(index, layer); };
                submit(std::move(r));
            }
            noteItem("holefill.pick." + std::to_string(k + 1));
            ImGui::EndGroup();
        }
    }
    if (ImGui::Button("Refine the pick") && !preview_images_.empty() &&
        previews_generation_ + 1 <= static_cast<int>(fill->choices.size())) {
        ++previews_generation_;
        releasePreviewImages();
    }
    ImGui::SameLine();
    if (ImGui::Button("Done")) previews_layer_ = -1;
    noteItem("holefill.done");
    ImGui::End();
}

}  // namespace terrasynth::editor
