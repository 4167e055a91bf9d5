// The exemplars panel: a hillshaded thumbnail of every exemplar with its terrain type, and a lasso
// on a thumbnail to copy a piece of real terrain into the extent (Gain et al. 2015 s5.3, fig. 8).
#include "editor_app.h"
#include "thumbnails.h"

namespace terrasynth::editor {
namespace {
constexpr float kRightWidth = 310.0f, kStatusHeight = 26.0f, kThumb = 136.0f;
constexpr ImGuiWindowFlags kPanelFlags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse;
}  // namespace

void EditorApp::drawExemplarsPanel() {
    const ExemplarDatabase& db = *view_->database;
    if (exemplar_images_.empty()) {
        for (size_t i = 0; i < db.exemplars.size(); ++i) {
            const Picture p = hillshadePicture(exemplarHeights(db, static_cast<int>(i)), 192);
            exemplar_images_.push_back(host_.uploadImage(p.rgba, p.width, p.height));
            exemplar_sizes_.push_back(ImVec2(static_cast<float>(p.width), static_cast<float>(p.height)));
        }
    }
    const float top = ImGui::GetFrameHeight();
    const float h = host_.height() - top - kStatusHeight;
    ImGui::SetNextWindowPos(ImVec2(host_.width() - kRightWidth, top + 0.55f * h), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(kRightWidth, 0.45f * h), ImGuiCond_Always);
    ImGui::Begin("Exemplars", nullptr, kPanelFlags);
    ImGui::TextDisabled("Lasso on a thumbnail to paste real terrain");
    for (size_t i = 0; i < exemplar_images_.size(); ++i) {
        if (i % 2) ImGui::SameLine();
        ImGui::BeginGroup();
        const ImVec2 size = exemplar_sizes_[i];
        const float scale = kThumb / std::max(size.x, size.y);
        const ImVec2 shown(size.x * scale, size.y * scale);
        const ImVec2 origin = ImGui::GetCursorScreenPos();
        ImGui::Image(exemplar_images_[i], shown);
        // The lasso: the image is an invisible button so ImGui owns the drag.
        ImGui::SetCursorScreenPos(origin);
        ImGui::PushID(static_cast<int>(i));
        ImGui::InvisibleButton("lasso", shown);
        ImGui::PopID();
        noteItem("exemplar." + std::to_string(i));
        const AtlasRect& rect = db.levels[0].rects[i];
        const float to_px_x = rect.width / shown.x, to_px_y = rect.height / shown.y;
        if (ImGui::IsItemActive()) {
            if (thumbnail_lasso_ != static_cast<int>(i)) {
                thumbnail_lasso_ = static_cast<int>(i);
                thumbnail_lasso_px_.clear();
            }
            const ImVec2 m = ImGui::GetIO().MousePos;
            const double px = std::clamp((m.x - origin.x) * to_px_x, 0.0f, rect.width - 1.0f);
            const double py = std::clamp((m.y - origin.y) * to_px_y, 0.0f, rect.height - 1.0f);
            if (thumbnail_lasso_px_.empty() || std::hypot(px - thumbnail_lasso_px_.back().first, py - thumbnail_lasso_px_.back().second) > 2.0)
                thumbnail_lasso_px_.push_back({px, py});
        }
        if (ImGui::IsItemDeactivated() && thumbnail_lasso_ == static_cast<int>(i)) {
            if (thumbnail_lasso_px_.size() >= 3) {
                copied_.outline = decimate(thumbnail_lasso_px_, 2.0);
                copied_.exemplar = static_cast<int>(i);
                selectTool("paste");
                setStatus("copied from " + db.exemplars[i].name + ": click the terrain where it goes", false);
            }
            thumbnail_lasso_ = -1;
        }
        // The lasso in progress, or the copied piece, over its thumbnail.
        const Polyline* shown_lasso = thumbnail_lasso_ == static_cast<int>(i) ? &thumbnail_lasso_px_
                                      : copied_.exemplar == static_cast<int>(i) ? &copied_.outline : nullptr;
        if (shown_lasso && shown_lasso->size() > 1) {
            ImDrawList* dl = ImGui::GetWindowDrawList();
            std::vector<ImVec2> points;
            for (const auto& p : *shown_lasso)
                points.push_back(ImVec2(origin.x + static_cast<float>(p.first) / to_px_x, origin.y + static_cast<float>(p.second) / to_px_y));
            dl->AddPolyline(points.data(), static_cast<int>(points.size()), IM_COL32(255, 230, 80, 255),
                            thumbnail_lasso_ < 0 ? ImDrawFlags_Closed : 0, 2.0f);
        }
        const int type = i < db.exemplar_type.size() ? db.exemplar_type[i] : -1;
        ImGui::TextWrapped("%s", db.exemplars[i].name.c_str());
        if (type >= 0 && type < static_cast<int>(db.type_names.size())) ImGui::TextDisabled("%s", db.type_names[static_cast<size_t>(type)].c_str());
        ImGui::EndGroup();
    }
    ImGui::End();
}

}  // namespace terrasynth::editor
