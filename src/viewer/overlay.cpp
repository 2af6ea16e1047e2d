#include "viewer/overlay.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <imgui.h>

#include "viewer/readout.h"

namespace whisker {

namespace {

ImU32 rgb(const float c[3]) {
  return IM_COL32(int(c[0] * 255.0f), int(c[1] * 255.0f), int(c[2] * 255.0f), 255);
}

// The false-colour scale of the noise view: 0.1 % to 100 %, log.
void noise_legend(const ImageArea& a) {
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  const float scale = ImGui::GetIO().FontGlobalScale, line = ImGui::GetTextLineHeight();
  const float w = std::min(a.w - 16.0f, 240.0f * scale), bar = 12.0f * scale;
  const ImVec2 p0(a.x + 8.0f, a.y + a.h - 8.0f - bar - 2.0f * line - 8.0f);
  dl->AddRectFilled(ImVec2(p0.x - 4, p0.y - 4),
                    ImVec2(p0.x + w + 4, p0.y + bar + 2.0f * line + 6.0f),
                    IM_COL32(0, 0, 0, 190), 3.0f);
  dl->AddText(p0, IM_COL32(230, 230, 230, 255), "noise per pixel (error / mean)");
  const float y0 = p0.y + line + 2.0f;
  const int steps = 48;
  for (int k = 0; k < steps; ++k) {
    float c0[3], c1[3];
    heat_colour(float(k) / steps, c0);
    heat_colour(float(k + 1) / steps, c1);
    dl->AddRectFilledMultiColor(ImVec2(p0.x + w * k / steps, y0),
                                ImVec2(p0.x + w * (k + 1) / steps, y0 + bar), rgb(c0), rgb(c1),
                                rgb(c1), rgb(c0));
  }
  const char* labels[] = {"0.1%", "1%", "10%", "100%"};
  for (int k = 0; k < 4; ++k) {
    const float x = p0.x + w * k / 3.0f;
    const float tw = ImGui::CalcTextSize(labels[k]).x;
    dl->AddLine(ImVec2(x, y0 + bar), ImVec2(x, y0 + bar + 3.0f), IM_COL32(230, 230, 230, 255));
    dl->AddText(ImVec2(std::clamp(x - tw * 0.5f, p0.x, p0.x + w - tw), y0 + bar + 2.0f),
                IM_COL32(230, 230, 230, 255), labels[k]);
  }
}

// The debug views' one-line legend.
void debug_legend_box(const ViewerState& s, const ImageArea& a) {
  const std::string text = debug_legend(s.debug);
  if (text.empty()) return;
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  const ImVec2 size = ImGui::CalcTextSize(text.c_str());
  const ImVec2 p0(a.x + 8.0f, a.y + a.h - 8.0f - size.y);
  dl->AddRectFilled(ImVec2(p0.x - 4, p0.y - 3), ImVec2(p0.x + size.x + 4, p0.y + size.y + 3),
                    IM_COL32(0, 0, 0, 190), 3.0f);
  dl->AddText(p0, IM_COL32(230, 230, 230, 255), text.c_str());
}

void wipe_line(const ViewerState& s, const ImageArea& a) {
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  const float x = a.x + a.w * s.wipe;
  dl->AddLine(ImVec2(x, a.y), ImVec2(x, a.y + a.h), IM_COL32(255, 255, 255, 220), 2.0f);
  const ImVec2 pad(4.0f, 2.0f);
  const bool raw = s.compare == kCompareRawDenoised;
  const char* left = raw ? "raw" : "held";
  const char* right = raw ? "denoised" : "live";
  dl->AddRectFilled(ImVec2(x - ImGui::CalcTextSize(left).x - 2 * pad.x - 4, a.y + 4),
                    ImVec2(x - 4, a.y + 4 + ImGui::GetTextLineHeight() + 2 * pad.y),
                    IM_COL32(0, 0, 0, 170));
  dl->AddText(ImVec2(x - ImGui::CalcTextSize(left).x - pad.x - 4, a.y + 4 + pad.y),
              IM_COL32(255, 255, 255, 255), left);
  dl->AddRectFilled(ImVec2(x + 4, a.y + 4),
                    ImVec2(x + 4 + ImGui::CalcTextSize(right).x + 2 * pad.x,
                           a.y + 4 + ImGui::GetTextLineHeight() + 2 * pad.y),
                    IM_COL32(0, 0, 0, 170));
  dl->AddText(ImVec2(x + 4 + pad.x, a.y + 4 + pad.y), IM_COL32(255, 255, 255, 255), right);
}

// The pixel under the mouse: radiance, samples, standard error. Fills
// `shown` with the box and lines drawn.
void pixel_readout(const ViewerState& s, const ImageArea& a, ReadoutShown& shown) {
  const ImGuiIO& io = ImGui::GetIO();
  const ImVec2 m = io.MousePos;
  if (io.WantCaptureMouse || ImGui::IsAnyMouseDown() || a.w <= 0 || a.h <= 0) return;
  if (m.x < a.x || m.y < a.y || m.x >= a.x + a.w || m.y >= a.y + a.h) return;
  const float u = (m.x - a.x) / a.w;
  const Snapshot* left = u < s.wipe ? wipe_left(s) : nullptr;
  const bool held = s.held.spp > 0 && (s.compare == kCompareHeld || left == &s.held);
  // The live side reads what is shown (quick passes combined, viewer/blend.h).
  const Snapshot& sn = held ? s.held : left ? *left : s.shown.image.spp > 0 ? s.shown.image : s.snap;
  const int x = std::min(sn.width - 1, int(u * sn.width));
  const int y = std::min(sn.height - 1, int((m.y - a.y) / a.h * sn.height));
  const std::vector<std::string> lines = readout_lines(read_pixel(sn, x, y), x, y, held);
  // The box as these lines make it (the longest line, not a guess: "1024
  // samples ..." is wider than a luminance line), kept over the image,
  // never over the panel.
  const ImGuiStyle& st = ImGui::GetStyle();
  float text_w = 0.0f;
  for (const std::string& line : lines) text_w = std::max(text_w, ImGui::CalcTextSize(line.c_str()).x);
  const float w = text_w + 2.0f * (st.WindowPadding.x + st.PopupBorderSize);
  const float h = ImGui::GetTextLineHeightWithSpacing() * float(lines.size()) - st.ItemSpacing.y +
                  2.0f * (st.WindowPadding.y + st.PopupBorderSize);
  const BoxPlace at = place_readout(m.x, m.y, w, h, a.x, a.y, a.w, a.h);
  ImGui::SetNextWindowPos(ImVec2(at.x, at.y));
  ImGui::BeginTooltip();
  for (const std::string& line : lines) ImGui::TextUnformatted(line.c_str());
  const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
  ImGui::EndTooltip();
  shown = {true, pos.x, pos.y, size.x, size.y, lines};
}

// With the panel out of the way, one dim line says how to bring it back.
void panel_hint(const ImageArea& a) {
  const char* text = "panel hidden: Tab shows it";
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  const ImVec2 size = ImGui::CalcTextSize(text);
  const ImVec2 p0(a.x + 6.0f, a.y + 6.0f);
  dl->AddRectFilled(ImVec2(p0.x - 3, p0.y - 2), ImVec2(p0.x + size.x + 3, p0.y + size.y + 2),
                    IM_COL32(0, 0, 0, 150), 3.0f);
  dl->AddText(p0, IM_COL32(200, 200, 200, 255), text);
}

}  // namespace

void draw_image_overlays(const ViewerState& s, const ImageArea& area, bool readout,
                         ReadoutShown* shown) {
  ReadoutShown none;
  ReadoutShown& out = shown ? *shown : none;
  out = ReadoutShown{};
  if (area.w <= 0 || area.h <= 0) return;
  if (!s.panel_visible) panel_hint(area);
  if (s.display.mode == kViewNoise) noise_legend(area);
  if (s.display.mode >= kViewNormals) {
    debug_legend_box(s, area);
    return;  // the readout and the wipe are about the render
  }
  if (wipe_left(s)) wipe_line(s, area);
  if (readout) pixel_readout(s, area, out);
}

}  // namespace whisker
