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
  const char* left = "held";
  const char* right = "live";
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

// The pixel under the mouse: radiance, samples, standard error.
void pixel_readout(const ViewerState& s, const ImageArea& a) {
  const ImGuiIO& io = ImGui::GetIO();
  const ImVec2 m = io.MousePos;
  if (io.WantCaptureMouse || ImGui::IsAnyMouseDown() || a.w <= 0 || a.h <= 0) return;
  if (m.x < a.x || m.y < a.y || m.x >= a.x + a.w || m.y >= a.y + a.h) return;
  const float u = (m.x - a.x) / a.w;
  const bool held = s.held.spp > 0 && (s.compare == kCompareHeld ||
                                       (s.compare == kCompareWipe && u < s.wipe));
  // The live side reads what is shown (quick passes combined, viewer/blend.h).
  const Snapshot& sn = held ? s.held : s.shown.image.spp > 0 ? s.shown.image : s.snap;
  const int x = std::min(sn.width - 1, int(u * sn.width));
  const int y = std::min(sn.height - 1, int((m.y - a.y) / a.h * sn.height));
  const PixelReadout r = read_pixel(sn, x, y);
  // Over the image, never over the panel: left of the mouse near the right edge.
  const ImGuiStyle& st = ImGui::GetStyle();
  const float w = ImGui::CalcTextSize("luminance 1.234e+05 +- 1.23e+03 (12.3 %)").x + 2.0f * st.WindowPadding.x;
  const float h = ImGui::GetTextLineHeightWithSpacing() * 5.0f + 2.0f * st.WindowPadding.y;
  float px = m.x + 16.0f, py = m.y + 8.0f;
  if (px + w > a.x + a.w) px = std::max(a.x, m.x - 8.0f - w);
  if (py + h > a.y + a.h) py = std::max(a.y, m.y - 8.0f - h);
  ImGui::SetNextWindowPos(ImVec2(px, py));
  ImGui::BeginTooltip();
  ImGui::Text("pixel (%d, %d)%s", x, y, held ? "  [held image]" : "");
  ImGui::Text("radiance  %.4g  %.4g  %.4g", r.rgb[0], r.rgb[1], r.rgb[2]);
  if (r.std_error >= 0.0 && r.luminance > 0.0)
    ImGui::Text("luminance %.4g +- %.3g (%.3g %%)", r.luminance, r.std_error,
                100.0 * r.std_error / r.luminance);
  else if (r.std_error >= 0.0)
    ImGui::Text("luminance %.4g +- %.3g", r.luminance, r.std_error);
  else
    ImGui::Text("luminance %.4g  (error needs 2 samples)", r.luminance);
  ImGui::Text("%llu sample%s (std. error of the pixel mean)", (unsigned long long)r.samples,
              r.samples == 1 ? "" : "s");
  ImGui::EndTooltip();
}

}  // namespace

void draw_image_overlays(const ViewerState& s, const ImageArea& area, bool readout) {
  if (area.w <= 0 || area.h <= 0) return;
  if (s.display.mode == kViewNoise) noise_legend(area);
  if (s.display.mode >= kViewNormals) {
    debug_legend_box(s, area);
    return;  // the readout and the wipe are about the render
  }
  if (s.compare == kCompareWipe && s.held.spp > 0) wipe_line(s, area);
  if (readout) pixel_readout(s, area);
}

}  // namespace whisker
