#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include <imgui.h>
#include <imgui_stdlib.h>

#include "viewer/viewer_state.h"

namespace whisker {

float report_exposure() { return 1.0f / std::pow(255.0f, 2.2f); }

// 1234567 -> "1.23 M".
static std::string human(double v) {
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

static void stats(ViewerState& s, double now) {
  const Snapshot& sn = s.snap;
  const bool stale = sn.generation != s.generation;
  const char* status = s.paused           ? "paused"
                       : sn.preview       ? "preview (1 sample per 4x4 block)"
                       : sn.done          ? "done (target reached)"
                                          : "rendering";
  ImGui::Text("%s  %dx%d  %s", s.scene_label.c_str(), sn.width, sn.height, status);
  const double secs = sn.seconds > 0.0 ? sn.seconds : 0.0;
  ImGui::Text("%llu spp   %llu passes   %.2f passes/s%s", (unsigned long long)sn.spp,
              (unsigned long long)sn.passes, secs > 0.0 ? sn.passes / secs : 0.0,
              stale ? "  (before the edit)" : "");
  ImGui::Text("%s rays/s   render %.1f s   since change %.1f s",
              human(secs > 0.0 ? sn.rays / secs : 0.0).c_str(), secs, now - s.last_change);
  if (std::isfinite(s.rse))
    ImGui::Text("rel. std. error  %.3g %%", 100.0 * s.rse);
  else
    ImGui::Text("rel. std. error  n/a (needs 2 spp)");
  if (sn.nan_count)
    ImGui::TextColored(ImVec4(1, 0.4f, 0.3f, 1), "NaN/Inf dropped %llu",
                       (unsigned long long)sn.nan_count);
  else
    ImGui::Text("NaN/Inf dropped 0");
  ImGui::SameLine();
  if (s.nodes)
    ImGui::Text("  triangles %zu  BVH nodes %zu", s.triangles, s.nodes);
  else
    ImGui::Text("  triangles %zu", s.triangles);
  if (s.frame_ms_avg > 0.0f)
    ImGui::Text("UI frame %.1f ms (mean of the last 30 drawn)", s.frame_ms_avg);
  // The error against render time, log scale, this generation only.
  if (s.rse_history.size() >= 2) {
    char overlay[48];
    std::snprintf(overlay, sizeof overlay, "log10 rel. error, per pass");
    ImGui::PlotLines("##rse", s.rse_history.data(), int(s.rse_history.size()), 0, overlay,
                     FLT_MAX, FLT_MAX, ImVec2(ImGui::GetContentRegionAvail().x, 40.0f * ImGui::GetIO().FontGlobalScale));
  }
}

static bool material_editor(Material& m, float* radius, float* inner_radius) {
  bool changed = false;
  if (ImGui::BeginCombo("material", to_string(m.kind))) {
    for (const auto& [kind, name] : enum_names(m.kind)) {
      if (kind == MaterialKind::HollowGlass && !inner_radius) continue;  // spheres only
      if (ImGui::Selectable(name, kind == m.kind) && kind != m.kind) {
        m.kind = kind;
        changed = true;
      }
    }
    ImGui::EndCombo();
  }
  if (changed) {
    // A hollow sphere needs a bubble: the report's 9.8 inside 10.
    if (inner_radius && m.kind == MaterialKind::HollowGlass && radius &&
        (*inner_radius <= 0.0f || *inner_radius >= *radius))
      *inner_radius = 0.98f * *radius;
  }
  if (m.kind == MaterialKind::Diffuse)
    changed |= ImGui::ColorEdit3("albedo", &m.albedo.x, ImGuiColorEditFlags_Float);
  if (m.kind == MaterialKind::Glass || m.kind == MaterialKind::HollowGlass)
    changed |= ImGui::DragFloat("refractive index", &m.ior, 0.005f, 1.0f, 3.0f, "%.3f");
  if (inner_radius && radius && m.kind == MaterialKind::HollowGlass)
    changed |= ImGui::DragFloat("bubble radius", inner_radius, 0.02f, 0.0f,
                                *radius, "%.2f");
  return changed;
}

// A checkbox per boolean setting of the table, its help as the tooltip.
static void setting_checkboxes(RenderSettings& r) {
  int boxes = 0;
  for (const SettingField& f : setting_fields()) {
    if (const auto* m = std::get_if<bool RenderSettings::*>(&f.member)) {
      if (boxes++ % 2) ImGui::SameLine(ImGui::GetContentRegionAvail().x * 0.5f);
      ImGui::Checkbox(f.key, &(r.*(*m)));
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", f.help);
    }
  }
}

// Pause, restart and save, and the last load / save message.
static void controls(const ViewerState& s, PanelRequests& req) {
  if (ImGui::Button(s.paused ? "Resume (Space)" : "Pause (Space)")) req.toggle_pause = true;
  ImGui::SameLine();
  if (ImGui::Button("Restart (R)")) req.restart = true;
  ImGui::SameLine();
  if (ImGui::Button("Save (S)")) req.save = true;
  if (!s.message.empty()) {
    if (s.message_is_error)
      ImGui::TextColored(ImVec4(1, 0.4f, 0.3f, 1), "%s", s.message.c_str());
    else
      ImGui::TextWrapped("%s", s.message.c_str());
  }
}

static void display_section(ViewerState& s) {
  if (!ImGui::CollapsingHeader("Display", ImGuiTreeNodeFlags_DefaultOpen)) return;
  ImGui::SliderFloat("exposure (stops)", &s.exposure_stops, -12.0f, 12.0f, "%+.1f");
  ImGui::SliderFloat("gamma", &s.display.gamma, 1.0f, 3.0f, "%.2f");
  static const char* modes[] = {"image", "noise (rel. std. error)"};
  ImGui::Combo("view", &s.display.mode, modes, 2);
  if (ImGui::Button("Report mapping")) {
    s.exposure_stops = 0.0f;
    s.display.gamma = 2.2f;
    s.display.mode = 0;
  }
}

static void scene_section(ViewerState& s, PanelRequests& req) {
  if (!ImGui::CollapsingHeader("Scene", ImGuiTreeNodeFlags_DefaultOpen)) return;
  if (ImGui::BeginCombo("bundled", s.scene_label.c_str())) {
    for (const std::string& name : s.scene_names)
      if (ImGui::Selectable(name.c_str(), name == s.scene_label)) req.load_scene = name;
    ImGui::EndCombo();
  }
  const bool enter = ImGui::InputText("path", &s.path_field,
                                      ImGuiInputTextFlags_EnterReturnsTrue);
  ImGui::SameLine();
  if ((ImGui::Button("Load") || enter) && !s.path_field.empty())
    req.load_scene = s.path_field;
}

static void light_section(PointLight& light) {
  if (!ImGui::CollapsingHeader("Light", ImGuiTreeNodeFlags_DefaultOpen)) return;
  ImGui::DragFloat3("position", &light.position.x, 0.25f, 0.0f, 0.0f, "%.2f");
  ImGui::DragFloat("intensity", &light.intensity, light.intensity * 0.005f + 1.0f,
                   0.0f, 1e14f, "%.3g", ImGuiSliderFlags_Logarithmic);
}

// The render settings' own widgets, one per setting, in one row of
// checkboxes and then sliders.
static void settings_widgets(RenderSettings& r) {
  setting_checkboxes(r);
  ImGui::SliderInt("max depth", &r.max_depth, 0, 16);
  ImGui::SliderInt("samples/pass", &r.spp, 1, 64);
}

// Splitting: paths per sample from its first and second diffuse hits.
static void split_widgets(RenderSettings& r) {
  static const std::vector<int> kChoices[] = {{1}, {4}, {4, 4}, {8, 4}};
  static const char* const kNames[] = {"1 (the report's)", "4", "4 x 4 (default)", "8 x 4"};
  int current = -1;
  for (int k = 0; k < 4; ++k)
    if (r.split == kChoices[k]) current = k;
  const std::string preview =
      current >= 0 ? kNames[current] : split_to_string(r.split) + " (command line)";
  if (ImGui::BeginCombo("paths/sample", preview.c_str())) {
    for (int k = 0; k < 4; ++k)
      if (ImGui::Selectable(kNames[k], k == current)) r.split = kChoices[k];
    ImGui::EndCombo();
  }
  // Channel weights of the split (RenderSettings::split_weights).
  const SettingField& w = setting_field("split_weights");
  ImGui::SliderFloat3("split r,g,b", &r.split_weights.x, float(w.lo), float(w.hi), "%.2f",
                      ImGuiSliderFlags_AlwaysClamp);
}

// Applied on release: each change restarts the worker pool.
static void threads_slider(ViewerState& s, PanelRequests& req) {
  const int hw = int(std::max(1u, std::thread::hardware_concurrency()));
  if (s.threads_edit <= 0) s.threads_edit = s.threads;
  ImGui::SliderInt("threads", &s.threads_edit, 1, std::max(hw, s.threads));
  if (ImGui::IsItemDeactivatedAfterEdit() && s.threads_edit != s.threads)
    req.threads = s.threads_edit;
  if (!ImGui::IsItemActive() && req.threads == 0) s.threads_edit = s.threads;
}

static void sampling_section(ViewerState& s, PanelRequests& req) {
  if (!ImGui::CollapsingHeader("Sampling", ImGuiTreeNodeFlags_DefaultOpen)) return;
  RenderSettings& r = s.edited.settings;
  settings_widgets(r);
  split_widgets(r);
  if (ImGui::InputInt("target spp", &r.target_spp, 32, 256)) r.target_spp = std::max(0, r.target_spp);
  if (r.target_spp == 0) {
    ImGui::SameLine();
    ImGui::TextDisabled("(never stop)");
  }
  threads_slider(s, req);
}

static void camera_section(Camera& camera, PanelRequests& req) {
  if (!ImGui::CollapsingHeader("Camera", ImGuiTreeNodeFlags_DefaultOpen)) return;
  ImGui::DragFloat3("eye", &camera.position.x, 0.25f, 0.0f, 0.0f, "%.2f");
  ImGui::DragFloat3("look at", &camera.look_at.x, 0.25f, 0.0f, 0.0f, "%.2f");
  ImGui::SliderFloat("fov (deg)", &camera.fov_deg, 5.0f, 150.0f, "%.1f");
  if (ImGui::Button("Reset camera")) req.reset_camera = true;
  ImGui::SameLine();
  if (ImGui::Button("Print JSON (C)")) req.print_camera = true;
  ImGui::TextDisabled("left drag orbit, right/middle drag pan, wheel dolly");
}

static void objects_section(Scene& e) {
  if (!ImGui::CollapsingHeader("Objects")) return;
  for (std::size_t i = 0; i < e.spheres.size(); ++i) {
    SphereObject& sp = e.spheres[i];
    ImGui::PushID(int(i));
    const std::string label = sp.name.empty() ? "sphere " + std::to_string(i) : sp.name;
    if (ImGui::TreeNode(label.c_str())) {
      material_editor(sp.material, &sp.radius, &sp.inner_radius);
      ImGui::TreePop();
    }
    ImGui::PopID();
  }
  for (std::size_t i = 0; i < e.meshes.size(); ++i) {
    MeshObject& m = e.meshes[i];
    ImGui::PushID(int(1000000 + i));
    const std::string label = m.name.empty() ? "mesh " + std::to_string(i) : m.name;
    if (ImGui::TreeNode(label.c_str())) {
      material_editor(m.material, nullptr, nullptr);
      ImGui::TreePop();
    }
    ImGui::PopID();
  }
}

void draw_panel(ViewerState& s, float window_w, float window_h, float panel_w,
                double now, PanelRequests& req) {
  ImGui::SetNextWindowPos(ImVec2(window_w - panel_w, 0.0f));
  ImGui::SetNextWindowSize(ImVec2(panel_w, window_h));
  ImGui::Begin("Whisker", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                   ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoTitleBar |
                   ImGuiWindowFlags_NoBringToFrontOnFocus);
  ImGui::PushItemWidth(-130.0f * ImGui::GetIO().FontGlobalScale);

  stats(s, now);
  controls(s, req);
  display_section(s);
  scene_section(s, req);
  light_section(s.edited.light);
  sampling_section(s, req);
  camera_section(s.edited.camera, req);
  objects_section(s.edited);

  ImGui::PopItemWidth();
  ImGui::End();
}

}  // namespace whisker
