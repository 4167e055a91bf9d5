#include "hud.h"

#include <imgui.h>

namespace terrasynth::game {
namespace {
constexpr ImGuiWindowFlags kPanel = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                    ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                    ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoMove;
}

void drawHud(const HudData& d) {
    ImGui::SetNextWindowPos(ImVec2(10, 10));
    ImGui::SetNextWindowBgAlpha(0.45f);
    ImGui::Begin("##flight", nullptr, kPanel);
    ImGui::Text("speed     %6.0f km/h  (%3.0f m/s)", d.speed_ms * 3.6, d.speed_ms);
    ImGui::Text("altitude  %6.0f m", d.altitude_m);
    if (d.ground_known)
        ImGui::Text("above gnd %6.0f m%s", d.above_ground_m, d.ground_exact ? "" : " (approx.)");
    else
        ImGui::Text("above gnd      ? m");
    ImGui::Text("throttle  %5.0f %%%s", d.throttle * 100.0, d.autopilot ? "   AUTOPILOT" : "");
    ImGui::Separator();
    ImGui::Text("position  %.2f, %.2f km", d.x_km, d.y_km);
    ImGui::Text("seed      %u", d.seed);
    ImGui::Text("rings     %d", d.rings_collected);
    if (d.ring_ahead)
        ImGui::Text("next ring %.1f km, %+.0f deg", d.ring_distance_m / 1000.0, d.ring_bearing_deg);
    ImGui::Separator();
    ImGui::Text("tiles     %zu resident, %zu pending", d.resident_tiles, d.pending_tiles);
    ImGui::Text("triangles %.2f M", d.drawn_triangles / 1e6);
    ImGui::Text("frame     %.1f ms (%.0f fps)", d.frame_ms, d.frame_ms > 0.0 ? 1000.0 / d.frame_ms : 0.0);
    ImGui::End();

    if (!d.message.empty()) {
        const ImVec2 size = ImGui::GetIO().DisplaySize;
        ImGui::SetNextWindowPos(ImVec2(size.x * 0.5f, size.y * 0.25f), 0, ImVec2(0.5f, 0.5f));
        ImGui::SetNextWindowBgAlpha(0.6f);
        ImGui::Begin("##message", nullptr, kPanel);
        ImGui::TextUnformatted(d.message.c_str());
        ImGui::End();
    }
    const ImVec2 size = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(10, size.y - 10), 0, ImVec2(0.0f, 1.0f));
    ImGui::SetNextWindowBgAlpha(0.35f);
    ImGui::Begin("##keys", nullptr, kPanel);
    ImGui::TextUnformatted("W/S pitch  A/D roll  Q/E yaw  Shift/Ctrl throttle  R respawn  P autopilot  F1 HUD  Esc quit");
    ImGui::End();
}

void drawLoading(const std::string& stage, double progress, double elapsed_s) {
    const ImVec2 size = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(size.x * 0.5f, size.y * 0.5f), 0, ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowSize(ImVec2(size.x * 0.5f, 0.0f));
    ImGui::Begin("##loading", nullptr, kPanel & ~ImGuiWindowFlags_AlwaysAutoResize);
    ImGui::TextUnformatted("terrasynth: preparing the world");
    ImGui::TextUnformatted(stage.c_str());
    ImGui::ProgressBar(static_cast<float>(progress), ImVec2(-1.0f, 0.0f));
    ImGui::Text("%.1f s", elapsed_s);
    ImGui::End();
}

void drawFatal(const std::string& message) {
    const ImVec2 size = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(size.x * 0.5f, size.y * 0.5f), 0, ImVec2(0.5f, 0.5f));
    ImGui::Begin("##fatal", nullptr, kPanel);
    ImGui::TextUnformatted("terrasynth could not start:");
    ImGui::TextUnformatted(message.c_str());
    ImGui::End();
}

}  // namespace terrasynth::game
