#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <imgui.h>
#include <imgui_stdlib.h>

#include "viewer/hover_delay.h"
#include "viewer/panel_parts.h"
#include "viewer/readout.h"

namespace whisker {

namespace {
HoverDelay g_hover;
std::string g_tip_shown;  // this frame's tooltip, for the event log
}  // namespace

const std::string& tooltip_shown() { return g_tip_shown; }

void tooltips_frame() {
  g_tip_shown.clear();
  const ImGuiIO& io = ImGui::GetIO();
  g_hover.begin_frame(ImGui::GetTime(), io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f,
                      ImGui::IsAnyMouseDown());
}

bool tooltip_waiting() { return g_hover.waiting(); }

void tip(const char* text) {
  if (!ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) return;
  // The widget's place tells it from the others.
  const ImVec2 a = ImGui::GetItemRectMin();
  const auto key = (static_cast<unsigned long long>(std::lround(a.x * 4.0f)) << 32) ^
                   static_cast<unsigned long long>(std::lround(a.y * 4.0f));
  if (!g_hover.due(key)) return;
  g_tip_shown = text;
  ImGui::BeginTooltip();
  ImGui::PushTextWrapPos(ImGui::GetFontSize() * 24.0f);
  ImGui::TextUnformatted(text);
  ImGui::PopTextWrapPos();
  ImGui::EndTooltip();
}

namespace {

// 1234567 -> "1.23 M".
std::string human(double v) {
  const char* units[] = {"", " k", " M", " G", " T"};
  int u = 0;
  while (std::fabs(v) >= 1000.0 && u < 4) {
    v /= 1000.0;
    ++u;
  }
  char buf[32];
  std::snprintf(buf, sizeof buf, u ? "%.2f%s" : "%.0f%s", v, units[u]);
  return buf;
}

}  // namespace

std::string state_text(const ViewerState& s) {
  const Snapshot& sn = s.snap;
  if (s.paused) return "paused";
  if (s.stopped_gen == s.generation && !s.stop_note.empty()) return "stopped: " + s.stop_note;
  if (sn.done && sn.generation == s.generation) return deterministic_estimate(s.applied) ? "done: exact" : "done: target reached";
  // Quick passes after an edit (viewer/blend.h): full resolution, one path a sample.
  if (s.shown.quick_spp > 0 && s.shown.own_spp == 0)
    return "quick preview, " + std::to_string(s.shown.quick_spp) + " fast spp";
  if (s.shown.quick_spp > 0)
    return "rendering (+" + std::to_string(s.shown.quick_spp) + " fast spp)";
  return "rendering";
}

std::uint64_t shown_spp(const ViewerState& s) {
  const Snapshot& sn = s.snap;
  return sn.generation == s.generation && !sn.quick ? sn.spp : 0;
}

namespace {

ProgressInfo progress_of(const ViewerState& s) {
  const Snapshot& sn = s.snap;
  ProgressInput in;
  const bool same = sn.generation == s.generation && !sn.quick;
  in.spp_done = shown_spp(s);
  in.seconds_done = same ? sn.counters.seconds : 0.0;
  in.target_spp = s.applied.settings.target_spp;
  const auto& p = s.progress;
  // A finished pass is counted once it is published, not as in flight; a
  // quick pass (pass_spp 0) is not counted at all.
  if (p.rendering && p.generation == s.generation && !s.paused && p.pass_spp > 0 &&
      p.tiles_done < p.tiles_total) {
    in.pass_spp = p.pass_spp;
    in.tiles_done = p.tiles_done;
    in.tiles_total = p.tiles_total;
    in.pass_seconds = p.pass_seconds;
  }
  return estimate_progress(in);
}

// The bar toward the target (or through the pass without one), then time.
// Returns the samples per pixel the bar says.
std::uint64_t progress_lines(const ViewerState& s) {
  const ProgressInfo p = progress_of(s);
  const int target = s.applied.settings.target_spp;
  // The bar's fill moves with the pass in flight; its number is the
  // samples in the image, as the window's title says (with several samples
  // a pass, counting the pass in flight made it run ahead of the title).
  const unsigned long long spp = shown_spp(s);
  char overlay[96];
  if (target > 0)
    std::snprintf(overlay, sizeof overlay, "%llu / %d spp", spp, target);
  else
    std::snprintf(overlay, sizeof overlay, "%llu spp (no target)", spp);
  ImGui::ProgressBar(target > 0 ? float(p.fraction) : float(p.pass_fraction), ImVec2(-1, 0),
                     overlay);
  tip("Samples per pixel so far against the target (Sampling > target spp). "
      "Without a target the bar shows the pass in flight.");
  const auto& pr = s.progress;
  const bool in_pass = pr.rendering && pr.generation == s.generation && !s.paused &&
                       pr.pass_spp > 0 && pr.tiles_done < pr.tiles_total;
  // Short enough for the panel's width with hours on both clocks.
  char pass[48] = "tiles -";
  if (in_pass) std::snprintf(pass, sizeof pass, "tiles %d/%d", pr.tiles_done, pr.tiles_total);
  ImGui::Text("%s  elapsed %s  left %s", pass, format_duration(p.elapsed).c_str(),
              target <= 0 ? "-" : format_duration(p.eta).c_str());
  tip("A pass adds 'samples/pass' samples to every pixel, tile by tile ('tiles': the "
      "pass in flight); the image updates when a pass ends. Time left is estimated "
      "from the rate measured so far ('-' without a target).");
  const double pixels = double(std::max(0, s.snap.width)) * std::max(0, s.snap.height);
  // Rays and passes are counted when a pass is published: until the first
  // pass of these settings is, they are not known yet ("-"), not zero.
  const double secs = s.snap.generation == s.generation && !s.snap.quick ? s.snap.counters.seconds : 0.0;
  char rays[32] = "-", passes[32] = "-";
  if (secs > 0.0) {
    std::snprintf(rays, sizeof rays, "%s", human(s.snap.counters.rays / secs).c_str());
    std::snprintf(passes, sizeof passes, "%.2f", s.snap.counters.passes / secs);
  }
  ImGui::Text("%s samples/s  %s rays/s  %s passes/s",
              p.spp_per_second > 0.0 ? human(p.spp_per_second * pixels).c_str() : "-", rays,
              passes);
  tip("samples/s: camera samples (one per pixel per spp) per second. With splitting "
      "each sample continues as several paths (up to 16 with 4 x 4), so paths/s is "
      "higher. rays/s counts every ray traced: camera, bounce and shadow rays.");
  return spp;
}

// The relative error against passes, log scale, with its axes.
void error_plot(const ViewerState& s) {
  const float h = 56.0f * ImGui::GetIO().FontGlobalScale;
  const ImVec2 size(ImGui::GetContentRegionAvail().x, h);
  const ImVec2 p0 = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("##errorplot", size);
  tip("Relative standard error of the image mean after each pass of the current "
      "render (log scale). Halving it takes four times the samples.");
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const float left = 44.0f * ImGui::GetIO().FontGlobalScale, line = ImGui::GetTextLineHeight();
  const ImVec2 a(p0.x + left, p0.y + 2.0f), b(p0.x + size.x - 4.0f, p0.y + h - line - 2.0f);
  dl->AddRectFilled(a, b, IM_COL32(30, 30, 36, 255));
  dl->AddRect(a, b, IM_COL32(110, 110, 120, 255));
  const std::vector<float>& v = s.rse_history;
  const ImU32 text = IM_COL32(170, 170, 180, 255);
  if (v.size() < 2) {
    const bool exact = s.snap.generation == s.generation && s.snap.spp > 0 && deterministic_estimate(s.applied);
    dl->AddText(ImVec2(a.x + 6.0f, a.y + 6.0f), text,
                exact ? "exact: every pass gives the same image" : "the plot starts after pass 2");
    dl->AddText(ImVec2(a.x, b.y + 1.0f), text, "pass");
    return;
  }
  // Whole decades around the values (log10 of the error).
  const auto [lo_it, hi_it] = std::minmax_element(v.begin(), v.end());
  const float lo = std::floor(*lo_it), hi = std::max(lo + 1.0f, std::ceil(*hi_it));
  const auto y_of = [&](float l) { return b.y - (l - lo) / (hi - lo) * (b.y - a.y); };
  for (float d = lo; d <= hi + 0.01f; d += 1.0f) {
    char label[24];
    std::snprintf(label, sizeof label, "%g%%", 100.0 * std::pow(10.0, double(d)));
    const float y = y_of(d);
    dl->AddLine(ImVec2(a.x, y), ImVec2(b.x, y), IM_COL32(70, 70, 80, 255));
    dl->AddText(ImVec2(p0.x, y - line * 0.5f), text, label);
  }
  const std::size_t n = v.size();
  const auto x_of = [&](std::size_t k) { return a.x + (b.x - a.x) * float(k) / float(n - 1); };
  for (std::size_t k = 1; k < n; ++k)
    dl->AddLine(ImVec2(x_of(k - 1), y_of(v[k - 1])), ImVec2(x_of(k), y_of(v[k])),
                IM_COL32(120, 200, 255, 255), 1.5f);
  // The history ends at the last published pass; the first pass has no error.
  const unsigned long long last_pass = std::max<unsigned long long>(s.snap.counters.passes, n);
  char first[32], last[32];
  std::snprintf(first, sizeof first, "pass %llu", last_pass - n + 1);
  std::snprintf(last, sizeof last, "pass %llu", last_pass);
  dl->AddText(ImVec2(a.x, b.y + 1.0f), text, first);
  dl->AddText(ImVec2(b.x - ImGui::CalcTextSize(last).x, b.y + 1.0f), text, last);
}

}  // namespace

// The denoised image's estimated error beside the raw image's (render/
// denoise.h estimate_error, bias included), per pixel and in 8 px blocks,
// as a root mean square in % of the mean; one line.
void denoised_line(const ViewerState& s, bool stale) {
  const DenoisedFigures& f = s.denoised_figures;
  if (!stale && s.snap.spp > 0 && deterministic_estimate(s.applied)) {
    ImGui::Text("denoised: nothing to do, the image is exact");
  } else if (!showing_denoised(s)) {
    ImGui::Text("denoised: - (needs 2 spp)");
  } else if (!f.valid) {
    ImGui::Text("denoised from %llu spp; no error estimate (Sobol halves)",
                (unsigned long long)s.denoised.spp);
  } else {
    const auto pct = [](double mse, double mean) { return mean > 0 ? 100.0 * std::sqrt(mse) / mean : 0.0; };
    const ScaleError& p = f.pixel;
    const ScaleError& b = f.block;
    const bool better = p.denoised_better() && (b.scale < 8 || b.denoised_better());
    ImGui::Text("denoised %.2g %% (raw %.2g), 8 px %.2g (%.2g): %s",
                pct(p.denoised_mse, p.mean), pct(p.raw_mse, p.mean), pct(b.denoised_mse, b.mean),
                pct(b.raw_mse, b.mean), better ? "better" : "worse");
  }
  char text[640];
  std::snprintf(text, sizeof text,
                "The denoised image's estimated error, bias included, against the raw image's: "
                "root mean square per pixel and over 8 x 8 pixel blocks, in %% of the mean, from "
                "the render's two independent half images (each filtered half compared with the "
                "other). The default Sobol sampler's halves are not independent: --sampler "
                "independent gives the figures after the first moments. The filter took %.0f ms; "
                "the window's redraw %.1f ms.",
                f.seconds * 1e3, double(s.frame_ms_avg));
  tip(text);
}

std::uint64_t status_section(const ViewerState& s, double now) {
  const Snapshot& sn = s.snap;
  // "Before the edit": the numbers are an earlier generation's (none at the start).
  const bool stale = sn.generation != 0 && sn.generation != s.generation;
  ImGui::Text("%s  %dx%d  %s", s.scene_label.c_str(), s.applied.camera.width, s.applied.camera.height,
              state_text(s).c_str());
  const std::uint64_t bar_spp = progress_lines(s);
  if (!stale && sn.spp > 0 && deterministic_estimate(s.applied))
    ImGui::Text("noise: none, exact (a deterministic estimate)");
  else if (std::isfinite(s.rse))
    ImGui::Text("noise: %.3g %% of the mean%s", 100.0 * s.rse, stale ? "  (before the edit)" : "");
  else if (!stale && sn.generation != 0 && sn.spp >= 2)
    ImGui::Text("noise: - (a black image: no light reaches it)");
  else
    ImGui::Text("noise: - (needs 2 spp)%s", stale ? "  (before the edit)" : "");
  tip("Relative standard error of the image mean: how far the average brightness may "
      "still be off, from the spread of each pixel's samples. It falls as 1/sqrt(spp). "
      "'(before the edit)' means the image still shows the previous settings.");
  error_plot(s);
  ImGui::Text("NaN/Inf dropped %llu  triangles %zu  since edit %.1f s",
              (unsigned long long)sn.counters.nan_count, triangle_count(s.applied), now - s.last_change);
  tip("Samples that came out not-a-number or infinite are dropped and counted here. "
      "'since edit': time since the last change that restarted the render.");
  // One line for the two, so the panel below never moves: with the denoised
  // view on, its error takes the window's redraw time's place.
  if (s.denoised_view) {
    denoised_line(s, stale);
    return bar_spp;
  }
  if (s.frame_ms_avg > 0.0f)
    ImGui::Text("window redraw %.1f ms", s.frame_ms_avg);
  else
    ImGui::Text("window redraw -");
  tip("Time the viewer takes to draw one frame of this window (mean of the last 30), "
      "not the render time. Rendering runs on its own threads.");
  return bar_spp;
}

void controls(const ViewerState& s, PanelRequests& req) {
  if (ImGui::Button(s.paused ? "Resume (Space)" : "Pause (Space)")) req.toggle_pause = true;
  tip("Stop or continue adding samples; the image is kept.");
  ImGui::SameLine();
  if (ImGui::Button("Restart (R)")) req.restart = true;
  tip("Throw the samples away and render from the first pass.");
  ImGui::SameLine();
  if (ImGui::Button("Save (S)")) req.save = true;
  tip("Write the image as shown (exposure, tone curve, view) as PNG, and the radiance "
      "as a float image, into the folder under 'Save'. An existing file is never "
      "overwritten: a free name (-2, -3, ...) is taken and reported.");
  ImGui::BeginDisabled(!s.history.can_undo());
  if (ImGui::Button("Undo (Ctrl+Z)")) req.undo = true;
  ImGui::EndDisabled();
  tip("Take back the last edit (a whole drag or typed number is one step). "
      "Display settings are not edits.");
  ImGui::SameLine();
  ImGui::BeginDisabled(!s.history.can_redo());
  if (ImGui::Button("Redo (Ctrl+Y)")) req.redo = true;
  ImGui::EndDisabled();
  tip("Do again what Undo took back.");
  ImGui::SameLine();
  bool denoised = s.denoised_view;
  if (ImGui::Checkbox("Denoised (D)", &denoised)) req.toggle_denoised = true;
  tip("Show a denoised copy of the image (edge-avoiding a-trous wavelets guided by the "
      "albedo, normal and depth of the first hit) instead of the raw render. The raw "
      "render goes on unchanged; Save writes the image shown, named -denoised.");
  // Two lines, always there, wrapped: a message never moves what is below.
  const float h = ImGui::GetTextLineHeightWithSpacing() * 2.0f + 4.0f;
  ImGui::BeginChild("##message", ImVec2(0, h), false, ImGuiWindowFlags_NoScrollbar);
  ImGui::PushTextWrapPos(0.0f);
  if (s.message_is_error) ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 0.45f, 0.35f, 1));
  ImGui::TextUnformatted(s.message.c_str());
  if (s.message_is_error) ImGui::PopStyleColor();
  ImGui::PopTextWrapPos();
  ImGui::EndChild();
  if (!s.message.empty()) tip(s.message.c_str());
}

void save_section(ViewerState& s, PanelRequests& req) {
  if (!ImGui::CollapsingHeader("Save")) return;
  ImGui::InputText("folder", &s.save_dir);
  tip("Folder Save writes into (created if missing). '.' is the folder the viewer "
      "was started from.");
  ImGui::InputTextWithHint("name", (s.scene_label + "-<spp>spp").c_str(), &s.save_name);
  tip("File name without extension. Empty: the scene's name and the samples per "
      "pixel. If the file exists, -2, -3, ... is added.");
  ImGui::Checkbox("float file in display units", &s.save_display_units);
  tip("The float image (.exr) beside the PNG: off, radiance in scene units (the cat's "
      "are in the hundreds of thousands); on, 1.0 = the PNG's white (255^2.2 radiance), "
      "so an HDR viewer at exposure 0 shows what the report's mapping shows. Its header "
      "records the scene, samples, seed, camera, settings and render time.");
  if (ImGui::Button("Save scene")) req.save_scene = true;
  tip("Write the scene with your edits (objects, light, camera, settings) as a scene "
      "file (.json) into the folder: load it later with Scene > path, or "
      "whisker --scene FILE. Named like the image, or SCENE-edited.");
}

void compare_section(ViewerState& s, PanelRequests& req) {
  if (!ImGui::CollapsingHeader("Compare (A/B)")) return;
  if (ImGui::Button("Hold this image")) req.hold = true;
  tip("Keep a copy of the image as it is now, to compare with the live render after "
      "an edit (e.g. Fresnel on against off at the same samples per pixel).");
  ImGui::SameLine();
  if (s.held.spp > 0) {
    // What fits beside the button, ending in "..." where the note is cut;
    // the whole note in the tooltip.
    const std::string note = "held: " + s.held_note;
    const float room = ImGui::GetContentRegionAvail().x;
    std::string shown = note;
    while (shown.size() > 4 && ImGui::CalcTextSize(shown.c_str()).x > room)
      shown = note.substr(0, shown.size() - 4) + "...";
    ImGui::TextDisabled("%s", shown.c_str());
    if (shown != note) tip(note.c_str());
  } else {
    ImGui::TextDisabled("nothing held");
  }
  ImGui::BeginDisabled(s.held.spp == 0 && !s.denoised_view);
  static const char* modes[] = {"live only", "held only", "wipe: held left, live right",
                                "wipe: raw left, denoised right"};
  ImGui::Combo("show", &s.compare, modes, 4);
  tip("What the image area shows: the live render, the held image, or two images split "
      "at the wipe line: the held one and the live one, or (with Denoised on) the live "
      "raw image and its denoised copy.");
  ImGui::BeginDisabled(s.compare != kCompareWipe && s.compare != kCompareRawDenoised);
  ImGui::SliderFloat("wipe", &s.wipe, 0.0f, 1.0f, "%.2f");
  tip("Where the left image ends and the right one begins.");
  ImGui::EndDisabled();
  ImGui::EndDisabled();
}

}  // namespace whisker

namespace whisker {

void confirm_load_popup(ViewerState& s, PanelRequests& req) {
  if (s.pending_load.empty()) return;
  if (!ImGui::IsPopupOpen("Discard the edits?")) ImGui::OpenPopup("Discard the edits?");
  if (!ImGui::BeginPopupModal("Discard the edits?", nullptr, ImGuiWindowFlags_AlwaysAutoResize))
    return;
  ImGui::Text("Loading %s replaces the current scene", s.pending_load.c_str());
  ImGui::Text("and its edits (Save > Save scene keeps them).");
  if (ImGui::Button("Discard and load")) {
    req.confirm_load = true;
    ImGui::CloseCurrentPopup();
  }
  ImGui::SameLine();
  if (ImGui::Button("Cancel")) {
    s.pending_load.clear();
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
}

void confirm_quit_popup(ViewerState& s, PanelRequests& req) {
  if (!s.pending_quit) return;
  if (!ImGui::IsPopupOpen("Quit and discard the edits?")) ImGui::OpenPopup("Quit and discard the edits?");
  if (!ImGui::BeginPopupModal("Quit and discard the edits?", nullptr, ImGuiWindowFlags_AlwaysAutoResize))
    return;
  ImGui::Text("The scene has edits that are not saved (Save > Save scene keeps them).");
  // Enter quits, Esc (the viewer's close_popups) stays.
  if (ImGui::Button("Discard and quit") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Enter))) {
    req.confirm_quit = true;
    ImGui::CloseCurrentPopup();
  }
  ImGui::SameLine();
  if (ImGui::Button("Cancel")) {
    s.pending_quit = false;
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
}

}  // namespace whisker
