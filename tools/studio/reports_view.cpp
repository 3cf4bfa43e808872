#include "reports_view.h"

#include <imgui.h>

#include <algorithm>
#include <filesystem>

#include "core/image.h"

namespace candela::studio {

ReportsView::ReportsView(const std::string& model) {
  if (model.rfind("builtin:", 0) == 0) return;
  folder_ = model + ".report";
  std::error_code ec;
  if (!std::filesystem::is_directory(folder_, ec)) return;
  for (const auto& e : std::filesystem::directory_iterator(folder_, ec)) {
    if (e.path().extension() != ".png") continue;
    Report r;
    r.name = e.path().filename().string();
    r.path = e.path().string();
    reports_.push_back(std::move(r));
  }
  std::sort(reports_.begin(), reports_.end(),
            [](const Report& a, const Report& b) { return a.name < b.name; });
}

void ReportsView::load(Report& r) {
  r.tried = true;
  try {
    const Image img = read_png(r.path, 4);
    r.texture = upload_rgba8(img.width, img.height, img.pixels.data(), true);
    r.width = img.width;
    r.height = img.height;
  } catch (const std::exception& e) {
    r.error = e.what();
  }
}

void ReportsView::draw(float width) {
  if (reports_.empty()) {
    ImGui::TextWrapped("No reports%s%s (candela-tool build writes them to MODEL.report/).",
                       folder_.empty() ? "" : " in ", folder_.c_str());
    return;
  }
  if (!ImGui::BeginTabBar("reports")) return;
  for (Report& r : reports_) {
    if (!ImGui::BeginTabItem(r.name.c_str())) continue;
    if (!r.tried) load(r);
    if (!r.error.empty()) {
      ImGui::TextWrapped("%s", r.error.c_str());
    } else if (r.width > 0) {
      const float w = std::max(16.0f, width);
      const auto id = reinterpret_cast<ImTextureID>(static_cast<intptr_t>(r.texture.get()));
      ImGui::Image(id, ImVec2(w, w * static_cast<float>(r.height) / static_cast<float>(r.width)));
      if (ImGui::IsItemHovered()) {
        // Hovered: the plot at its own size (its text is a 5x7 font), or as
        // large as the window holds.
        const ImVec2 room = ImGui::GetIO().DisplaySize;
        const float k = std::min({1.0f, (room.x - 24) / static_cast<float>(r.width),
                                  (room.y - 24) / static_cast<float>(r.height)});
        ImGui::BeginTooltip();
        ImGui::Image(id, ImVec2(k * static_cast<float>(r.width), k * static_cast<float>(r.height)));
        ImGui::EndTooltip();
      }
      ImGui::Text("%s, %dx%d (hover: full size)", r.name.c_str(), r.width, r.height);
    }
    ImGui::EndTabItem();
  }
  ImGui::EndTabBar();
}

}  // namespace candela::studio
