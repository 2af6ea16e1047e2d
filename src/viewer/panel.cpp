#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include <imgui.h>
#include <imgui_stdlib.h>

#include "viewer/panel_parts.h"
#include "viewer/viewer_state.h"

namespace whisker {

float report_exposure() { return 1.0f / std::pow(255.0f, 2.2f); }

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
  tip("diffuse: matte; mirror: perfect reflection; glass: solid refracting glass; "
      "hollow glass: a glass shell with an air bubble inside.");
  if (changed) {
    // A hollow sphere needs a bubble: the report's 9.8 inside 10.
    if (inner_radius && m.kind == MaterialKind::HollowGlass && radius &&
        (*inner_radius <= 0.0f || *inner_radius >= *radius))
      *inner_radius = 0.98f * *radius;
  }
  if (m.kind == MaterialKind::Diffuse)
    changed |= ImGui::ColorEdit3("albedo", &m.albedo.x, ImGuiColorEditFlags_Float | ImGuiColorEditFlags_NoTooltip);
  if (m.kind == MaterialKind::Diffuse) tip("Fraction of light reflected, per colour channel.");
  if (is_glass(m.kind))
    changed |= ImGui::DragFloat("refractive index", &m.ior, 0.005f, 1.0f, 3.0f, "%.3f",
                                ImGuiSliderFlags_AlwaysClamp);
  if (is_glass(m.kind))
    tip("How strongly the glass bends light: 1.0 air, 1.33 water, 1.5 window glass. "
        "Drag, or double-click to type.");
  if (inner_radius && radius && m.kind == MaterialKind::HollowGlass)
    changed |= ImGui::DragFloat("bubble radius", inner_radius, 0.02f, 0.0f,
                                *radius, "%.2f", ImGuiSliderFlags_AlwaysClamp);
  if (inner_radius && radius && m.kind == MaterialKind::HollowGlass)
    tip("Radius of the air bubble inside the sphere; the shell is the difference.");
  return changed;
}

// A checkbox per boolean setting of the table, its help as the tooltip.
static void setting_checkboxes(RenderSettings& r) {
  int boxes = 0;
  for (const SettingField& f : setting_fields()) {
    if (const auto* m = std::get_if<bool RenderSettings::*>(&f.member)) {
      if (boxes++ % 2) ImGui::SameLine(ImGui::GetContentRegionAvail().x * 0.5f);
      ImGui::Checkbox(f.label ? f.label : f.key, &(r.*(*m)));
      tip(f.help);
    }
  }
}

static void display_section(ViewerState& s) {
  if (!ImGui::CollapsingHeader("Display")) return;
  ImGui::SliderFloat("exposure (stops)", &s.exposure_stops, -12.0f, 12.0f, "%+.1f",
                     ImGuiSliderFlags_AlwaysClamp);
  tip("Brightness of the display in photographic stops: +1 doubles, -1 halves. "
      "0 is the report's mapping. Never restarts the render; Save uses it too.");
  ImGui::SliderFloat("gamma", &s.display.gamma, 1.0f, 3.0f, "%.2f", ImGuiSliderFlags_AlwaysClamp);
  tip("Display gamma; the report uses 2.2.");
  static const char* curves[] = {"report (clip at white)", "ACES filmic"};
  ImGui::Combo("tone curve", &s.display.tonemap, curves, 2);
  tip("How bright values map to the screen. 'report': linear, anything above white "
      "clips (the report's mapping). 'ACES filmic': highlights roll off smoothly "
      "(Narkowicz 2015 fit), after the exposure.");
  static const char* modes[] = {"image", "noise per pixel", "normals", "material colours",
                                "depth"};
  ImGui::Combo("view", &s.display.mode, modes, kViewModes);
  tip("'noise per pixel': each pixel's relative standard error in false colour, "
      "blue 0.1 % to red 100 % (log scale); black where a pixel has no light. "
      "'normals', 'material colours', 'depth': what the camera sees first through "
      "each pixel, to check geometry and materials. The legend is at the image's "
      "bottom left. Rendering goes on meanwhile.");
  if (ImGui::Button("Report mapping")) {
    s.exposure_stops = 0.0f;
    s.display.gamma = 2.2f;
    s.display.mode = kViewImage;
    s.display.tonemap = 0;
  }
  tip("Back to exposure 0, gamma 2.2, report tone curve, image view.");
  ImGui::SameLine();
  ImGui::Checkbox("pixel readout (I)", &s.readout_on);
  tip("The box over the image with the radiance, error and samples of the pixel under the "
      "pointer. It sits beside the pointer, on the side away from the image's centre.");
}

static void scene_section(ViewerState& s, PanelRequests& req) {
  if (!ImGui::CollapsingHeader("Scene", ImGuiTreeNodeFlags_DefaultOpen)) return;
  if (ImGui::BeginCombo("bundled", scene_choice(s).c_str())) {
    for (const std::string& name : s.scene_names)
      if (ImGui::Selectable(name.c_str(), name == s.bundled_scene)) req.load_scene = name;
    ImGui::EndCombo();
  }
  tip("The scenes that come with Whisker (assets/scenes). Loading one replaces the "
      "current scene and its settings. 'file: NAME': the scene came from another file.");
  const bool enter = ImGui::InputText("path", &s.path_field,
                                      ImGuiInputTextFlags_EnterReturnsTrue);
  tip("A scene file (.json) to load: type or paste the path, then Enter or Load.");
  ImGui::SameLine();
  if ((ImGui::Button("Load") || enter) && !s.path_field.empty())
    req.load_scene = s.path_field;
  tip("Load the scene file named in 'path'.");
}

// Three doubles (scene positions are double, scene.h), dragged or typed.
// A value typed past its range (Ctrl+click on a slider, a number box) is
// brought back into it, the command line's range for a setting, and the
// panel says what was typed and what was kept, as the command line refuses
// such a value.
template <class T>
static void keep_in_range(ViewerState& s, const char* label, T& v, double lo, double hi) {
  if (double(v) >= lo && double(v) <= hi) return;
  const T typed = v;
  v = double(v) < lo ? T(lo) : T(hi);
  char text[160];
  std::snprintf(text, sizeof text, "%s: must be in [%.6g, %.6g], got %.6g; kept %.6g", label, lo, hi,
                double(typed), double(v));
  s.message = text;
  s.message_is_error = true;
}
template <class T>
static void keep_in_range(ViewerState& s, const char* label, T& v, const char* key) {
  const SettingField& f = setting_field(key);
  keep_in_range(s, label, v, f.lo, f.option_hi > 0.0 ? f.option_hi : f.hi);
}

static void drag_position(const char* label, double* xyz) {
  ImGui::DragScalarN(label, ImGuiDataType_Double, xyz, 3, 0.25f, nullptr, nullptr, "%.2f");
}

static void light_section(ViewerState& s) {
  PointLight& light = s.edited.light;
  if (!ImGui::CollapsingHeader("Light", ImGuiTreeNodeFlags_DefaultOpen)) return;
  drag_position("position", &light.position.x);
  tip("Where the point light is (x, y, z in scene units). Drag a number sideways, "
      "or double-click it to type; a typed value applies on Enter.");
  ImGui::DragFloat("intensity", &light.intensity, light.intensity * 0.005f + 1.0f,
                   0.0f, 1e14f, "%.3g", ImGuiSliderFlags_Logarithmic);
  keep_in_range(s, "intensity", light.intensity, 0.0, 1e30);  // as --intensity
  tip("The light's power. Light falls off with the square of the distance, so "
      "scenes use large values (the cat: 2e10).");
}

// The render settings' own widgets, one per setting, in one row of
// checkboxes and then sliders.
static void settings_widgets(ViewerState& s) {
  RenderSettings& r = s.edited.settings;
  setting_checkboxes(r);
  ImGui::SliderInt("max depth", &r.max_depth, 0, 16);
  keep_in_range(s, "max depth", r.max_depth, "max_depth");
  tip("Most bounces a path may take (mirror, glass and, with indirect, diffuse).");
  ImGui::SliderInt("samples/pass", &r.spp, 1, 64);
  keep_in_range(s, "samples/pass", r.spp, "spp");
  tip("Samples per pixel each pass adds. More per pass: fewer, slower image updates.");
}

// Splitting: paths per sample from its first and second diffuse hits.
static void split_widgets(RenderSettings& r) {
  static const std::vector<int> kChoices[] = {{1}, {4}, {4, 2}, {4, 4}, {8, 4}};
  static const char* const kNames[] = {"1 (the report's)", "4", "4 x 2 (the cat)", "4 x 4 (default)",
                                       "8 x 4"};
  constexpr int kCount = 5;
  int current = -1;
  for (int k = 0; k < kCount; ++k)
    if (r.split == kChoices[k]) current = k;
  const std::string preview =
      current >= 0 ? kNames[current] : split_to_string(r.split) + " (command line)";
  // Splitting happens at diffuse bounces, which only indirect light follows.
  ImGui::BeginDisabled(!r.indirect);
  if (ImGui::BeginCombo("paths/sample", preview.c_str())) {
    for (int k = 0; k < kCount; ++k)
      if (ImGui::Selectable(kNames[k], k == current)) r.split = kChoices[k];
    ImGui::EndCombo();
  }
  tip(r.indirect ? "Splitting: at the first (and second) diffuse bounce a sample "
                   "continues as several paths, whose average is less noisy. 4 x 4: "
                   "4 at the first bounce, 4 each at the second, up to 16 paths."
                 : "Off because indirect light is off: paths split only at "
                   "diffuse bounces.");
  // Channel weights of the split (RenderSettings::split_weights).
  const SettingField& w = setting_field("split_weights");
  ImGui::SliderFloat3("split weights", &r.split_weights.x, float(w.lo), float(w.hi), "%.2f",
                      ImGuiSliderFlags_AlwaysClamp);
  tip(r.indirect ? "How much each colour channel (r, g, b) counts when deciding how "
                   "many paths to split into: a path carrying mostly low-weight colour "
                   "splits less (as --split-weights)."
                 : "Off because indirect light is off.");
  ImGui::EndDisabled();
}

// Applied on release: each change restarts the worker pool.
static void threads_slider(ViewerState& s, PanelRequests& req) {
  const int hw = int(std::max(1u, std::thread::hardware_concurrency()));
  if (s.threads_edit <= 0) s.threads_edit = s.threads;
  ImGui::SliderInt("threads", &s.threads_edit, 1, std::max(hw, s.threads));
  tip("Render threads; applied on release. The image does not depend on it.");
  if (ImGui::IsItemDeactivatedAfterEdit() && s.threads_edit != s.threads)
    req.threads = s.threads_edit;
  if (!ImGui::IsItemActive() && req.threads == 0) s.threads_edit = s.threads;
}

// Stop at a noise level or after a time: one line, applied when a field
// lets go of the keyboard.
static void stop_fields(ViewerState& s) {
  const float scale = ImGui::GetIO().FontGlobalScale;
  ImGui::AlignTextToFramePadding();
  ImGui::TextUnformatted("stop at");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(56.0f * scale);
  ImGui::InputFloat("% noise or##stopnoise", &s.stop_noise_field, 0.0f, 0.0f, "%g");
  if (!ImGui::IsItemActive()) s.stop_noise_field = s.stop_noise_pct = std::max(0.0f, s.stop_noise_field);
  tip("Stop this render once its noise (the line at the top, % of the mean) is at most this; "
      "0: never. An edit starts a new render, which stops there too. Raise 'target spp' or "
      "set 0 here to go on.");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(56.0f * scale);
  ImGui::InputFloat("s (0: off)##stopseconds", &s.stop_seconds_field, 0.0f, 0.0f, "%g");
  if (!ImGui::IsItemActive()) s.stop_seconds_field = s.stop_seconds = std::max(0.0f, s.stop_seconds_field);
  tip("Stop this render after this many seconds of render time (the 'elapsed' clock); 0: never. "
      "An edit starts a new render, which gets as long again.");
}

static bool scene_has_glass(const Scene& e) {
  const auto glass = [](const Material& m) {
    return is_glass(m.kind);
  };
  for (const SphereObject& sp : e.spheres)
    if (glass(sp.material)) return true;
  for (const MeshObject& m : e.meshes)
    if (glass(m.material)) return true;
  return false;
}

// One click to glass: every mesh of the scene (the cat) becomes glass, or
// back to what it was when loaded; Fresnel then has something to act on.
static void glass_toggle(ViewerState& s) {
  std::vector<MeshObject>& meshes = s.edited.meshes;
  bool glass = !meshes.empty();
  for (const MeshObject& m : meshes) glass = glass && m.material.kind == MaterialKind::Glass;
  if (!meshes.empty()) {
    if (ImGui::Checkbox(meshes.size() == 1 ? "glass mesh" : "glass meshes", &glass)) {
      for (std::size_t i = 0; i < meshes.size(); ++i) {
        Material before;
        if (i < s.initial.meshes.size() && s.initial.meshes[i].material.kind != MaterialKind::Glass)
          before = s.initial.meshes[i].material;
        Material g;
        g.kind = MaterialKind::Glass;
        meshes[i].material = glass ? g : before;
      }
    }
    tip("Make the scene's meshes (the cat) solid glass, refractive index 1.5, or give "
        "them back their material. With glass, Fresnel matters; the bundled "
        "glass-cat scene starts this way.");
  }
  // The note goes beside the checkbox, and only a note: with glass the next
  // widget (paths/sample) must start its own line, or it lands beside the
  // checkbox, its label cut off, and the widgets below move up a line.
  if (!scene_has_glass(s.edited)) {
    if (!meshes.empty()) ImGui::SameLine();
    ImGui::TextDisabled("(no glass: Fresnel does nothing)");
  }
}

static void sampling_section(ViewerState& s, PanelRequests& req) {
  if (!ImGui::CollapsingHeader("Sampling", ImGuiTreeNodeFlags_DefaultOpen)) return;
  RenderSettings& r = s.edited.settings;
  settings_widgets(s);
  glass_toggle(s);
  split_widgets(r);
  ImGui::InputInt("target spp", &r.target_spp, 32, 256);
  keep_in_range(s, "target spp", r.target_spp, "target_spp");
  tip("Stop at this many samples per pixel (0 = never stop). A typed number applies on "
      "Enter; raising it, or +, carries on from the current image.");
  threads_slider(s, req);
  stop_fields(s);
}

static void bookmarks(const ViewerState& s, PanelRequests& req) {
  if (ImGui::Button("Bookmark")) req.bookmark = true;
  tip("Remember this camera; the numbered buttons go back to it.");
  for (std::size_t k = 0; k < s.bookmarks.size() && k < 9; ++k) {
    ImGui::SameLine();
    ImGui::PushID(int(k));
    if (ImGui::Button(std::to_string(k + 1).c_str())) req.goto_bookmark = int(k);
    ImGui::PopID();
    tip("Go to this bookmarked camera.");
  }
}

static void camera_section(ViewerState& s, PanelRequests& req) {
  Camera& camera = s.edited.camera;
  if (!ImGui::CollapsingHeader("Camera")) return;
  drag_position("eye", &camera.position.x);
  tip("Camera position (x, y, z). Or left-drag on the image to orbit.");
  drag_position("look at", &camera.look_at.x);
  tip("The point the camera looks at and orbits around.");
  ImGui::SliderFloat("fov (deg)", &camera.fov_deg, 5.0f, 150.0f, "%.1f", ImGuiSliderFlags_AlwaysClamp);
  tip("Field of view in degrees: smaller zooms in.");
  if (ImGui::Button("Reset camera")) req.reset_camera = true;
  tip("Back to the camera of the scene as loaded.");
  ImGui::SameLine();
  if (ImGui::Button("Print JSON (C)")) req.print_camera = true;
  tip("Print the camera as scene-file JSON to the terminal, to paste into a scene.");
  bookmarks(s, req);
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

// "Camera outside the room: <why>." in red and a Reset button, when `why`
// is not empty; the button sets `reset`. `what`: "Camera", `thing`: "camera".
static void outside_warning(const char* what, const char* thing, const std::string& why, bool& reset) {
  if (why.empty()) return;
  ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 0.45f, 0.35f, 1));
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextUnformatted((std::string(what) + " outside the room: " + why + ".").c_str());
  ImGui::PopTextWrapPos();
  ImGui::PopStyleColor();
  if (ImGui::Button((std::string("Reset ") + thing + "##outside").c_str())) reset = true;
  tip((std::string("Back to the ") + thing + " of the scene as loaded (Ctrl+Z also takes the move back).").c_str());
}

void draw_panel(ViewerState& s, float window_w, float window_h, float panel_w,
                double now, PanelRequests& req) {
  tooltips_frame();
  if (panel_w <= 0.0f) {
    // Hidden (Tab, or a window too small for it): its questions still ask.
    confirm_load_popup(s, req);
    confirm_quit_popup(s, req);
    return;
  }
  ImGui::SetNextWindowPos(ImVec2(window_w - panel_w, 0.0f));
  ImGui::SetNextWindowSize(ImVec2(panel_w, window_h));
  ImGui::Begin("Whisker", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                   ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoTitleBar |
                   ImGuiWindowFlags_NoBringToFrontOnFocus);
  ImGui::PushItemWidth(-130.0f * ImGui::GetIO().FontGlobalScale);

  s.bar_spp = status_section(s, now);
  controls(s, req);
  // From outside the room the image is black or wrong: say so, and the way back.
  outside_warning("Camera", "camera", s.eye_outside, req.reset_camera);
  outside_warning("Light", "light", s.light_outside, req.reset_light);
  // The sections scroll on their own when the window is short; the status
  // lines above always stay in view.
  ImGui::BeginChild("##sections", ImVec2(0, 0), false);
  display_section(s);
  compare_section(s, req);
  save_section(s, req);
  scene_section(s, req);
  light_section(s);
  sampling_section(s, req);
  camera_section(s, req);
  objects_section(s.edited);
  ImGui::EndChild();

  confirm_load_popup(s, req);
  confirm_quit_popup(s, req);
  ImGui::PopItemWidth();
  ImGui::End();
}

}  // namespace whisker
