#include "ibfvs/viewer_panel.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <imgui.h>
#include <glm/geometric.hpp>

#include "ibfvs/core/support/names.h"
#include "ibfvs/core/support/text.h"

namespace ibfvs::app {
namespace {

// A combo box over an enum's name table; true when the choice changed.
template <class E>
bool enum_combo(const char* label, E& value) {
  const std::vector<EnumName<E>> entries = enum_entries<E>();
  int index = enum_index(value);
  const std::string preview(index >= 0 ? entries[static_cast<std::size_t>(index)].name : "?");
  bool changed = false;
  if (ImGui::BeginCombo(label, preview.c_str())) {
    for (std::size_t i = 0; i < entries.size(); ++i) {
      const std::string name(entries[i].name);
      if (ImGui::Selectable(name.c_str(), static_cast<int>(i) == index)) {
        changed = entries[i].value != value;
        value = entries[i].value;
      }
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip("%s", std::string(entries[i].description).c_str());
    }
    ImGui::EndCombo();
  }
  return changed;
}

}  // namespace

void ViewerPanel::draw(ViewerSession& viewer, bool& show, bool& show_help, double fps) {
  // A side bar left of the image (the window is that much wider), so it
  // never hides the mesh.
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(0, 0), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(static_cast<float>(kWidth), display.y), ImGuiCond_Always);
  char title[64];
  std::snprintf(title, sizeof title, "ibfvs %.0f fps###ibfvs", fps);
  ImGui::Begin(title, &show,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
  ImGui::PushItemWidth(130);
  Scene d = viewer.desc();
  bool changed = false;
  // Each slider spans its key's range and is named by its label (the keys'
  // table: key_range, key_label).
  const auto slider = [](const char* key, float& value, const char* format) {
    const KeyRange r = *key_range(key);
    return ImGui::SliderFloat(std::string(key_label(key)).c_str(), &value, r.min, r.max, format);
  };
  changed |= slider("alpha", d.alpha, "%.2f");
  changed |= slider("beta", d.beta, "%.2f");
  changed |= slider("vg", d.vg, "%.3f");
  changed |= enum_combo("profile", d.profile);
  // The display stage and the warp (docs/quality.md).
  changed |= slider("filter", d.filter, "%.1f");
  changed |= slider("contrast", d.contrast, "%.2f");
  changed |= enum_combo("resample", d.resample);
  // A moving mesh's series: whether its motion carries the texture (docs/data.md).
  if (viewer.scene().step_count > 1)
    changed |= enum_combo(std::string(key_label("field_frame")).c_str(), d.field_frame);
  const ImGuiColorEditFlags swatch = ImGuiColorEditFlags_NoInputs;
  changed |= ImGui::ColorEdit3("bg", &d.background.x, swatch);
  ImGui::SameLine();
  changed |= ImGui::ColorEdit3("surface", &d.surface_color.x, swatch);
  if (changed) viewer.apply_live(d);
  enum_combo("drag", viewer.drag_mode);
  bool locked = viewer.session().locked();
  if (ImGui::Checkbox("lock", &locked)) viewer.toggle_lock();
  ImGui::SameLine();
  ImGui::Checkbox("pause", &viewer.paused);
  if (ImGui::SmallButton("reset view")) viewer.camera().reset();
  ImGui::SameLine();
  if (ImGui::SmallButton("restart")) viewer.restart();
  ImGui::SameLine();
  if (ImGui::SmallButton("help")) show_help = !show_help;
  if (viewer.scene().step_count > 1) {
    // Unsteady data (months on the globe): play with pause, step, slide.
    float t = static_cast<float>(viewer.time);
    if (ImGui::SliderFloat("time", &t, 0.0f,
                           static_cast<float>(viewer.scene().step_count) - 0.01f)) {
      viewer.time = t;
      viewer.session().seek(viewer.time);
    }
    if (ImGui::SmallButton("<")) {  // the step before; from the first, the last
      viewer.time = std::floor(viewer.time) - 1.0;
      if (viewer.time < 0.0) viewer.time += static_cast<double>(viewer.scene().step_count);
    }
    ImGui::SameLine();
    if (ImGui::SmallButton(">")) viewer.time = std::floor(viewer.time) + 1.0;
    ImGui::SameLine();
    bool loop = viewer.desc().loop;
    if (ImGui::Checkbox("loop", &loop)) viewer.set("loop", loop ? "true" : "false");
    viewer.session().seek(viewer.time);
    viewer.time = viewer.session().time();  // as played: held at the last step, or looped
    ImGui::SameLine();
    const std::size_t step = static_cast<std::size_t>(viewer.time) % viewer.scene().step_count;
    const std::vector<std::string>& when = viewer.scene().step_labels;  // dates of netCDF steps
    ImGui::Text("step %zu of %zu", step, viewer.scene().step_count);
    if (step < when.size()) ImGui::Text("%s", when[step].c_str());  // a line of its own
  }
  if (ImGui::CollapsingHeader("More parameters")) draw_more_parameters(viewer);
  if (ImGui::CollapsingHeader("Styles and files")) draw_styles_and_files(viewer);
  if (ImGui::CollapsingHeader("Flow elements")) draw_elements(viewer);
  if (ImGui::CollapsingHeader("Save and record")) draw_save_and_record(viewer);
  if (!viewer.message.empty()) {
    ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + 200);
    ImGui::TextUnformatted(viewer.message.c_str());
    ImGui::PopTextWrapPos();
  }
  ImGui::PopItemWidth();
  ImGui::End();
}

// Scene file, screenshot, recording, an offscreen render at any size.
void ViewerPanel::draw_save_and_record(ViewerSession& viewer) {
  ImGui::Text("frame %d, %zu triangles", viewer.frame_count(),
              viewer.scene().mesh->triangle_count());
  char path[256];
  std::snprintf(path, sizeof path, "%s", save_path_.c_str());
  ImGui::SetNextItemWidth(140);
  if (ImGui::InputText("##scene file", path, sizeof path)) save_path_ = path;
  ImGui::SameLine();
  if (ImGui::SmallButton("save scene")) viewer.save_scene(save_path_);
  if (ImGui::SmallButton("screenshot")) {
    const std::string name = viewer.numbered_name(".png");
    viewer.screenshot(name);
  }
  ImGui::SameLine();
  if (ImGui::SmallButton(viewer.recording() ? "stop recording" : "record"))
    viewer.toggle_recording();
  ImGui::SetNextItemWidth(110);
  ImGui::InputInt2("##snapshot size", snapshot_size_);
  ImGui::SameLine();
  if (ImGui::SmallButton("render offscreen")) {
    const std::string name = viewer.numbered_name(".png");
    try {
      viewer.snapshot(std::clamp(snapshot_size_[0], 1, 16384),
                      std::clamp(snapshot_size_[1], 1, 16384), name);
    } catch (const std::exception& e) {
      viewer.message = std::string("error: ") + e.what();
    }
  }
}

// s, step, noise space, tangent mode, colour map and ranges.
void ViewerPanel::draw_more_parameters(ViewerSession& viewer) {
  Scene d = viewer.desc();
  // Logarithmic: the keys' spans (key_range) reach 64 pixels, the common
  // values are a few.
  const KeyRange scale = *key_range("scale"), step = *key_range("step");
  if (ImGui::SliderFloat(std::string(key_label("scale")).c_str(), &d.scale, scale.min, scale.max,
                         "%.2f", ImGuiSliderFlags_Logarithmic) &&
      d.scale != viewer.desc().scale) {
    viewer.set_noise_scale(d.scale);  // a new grid: the texture goes on
    return;
  }
  if (ImGui::SliderFloat(std::string(key_label("step")).c_str(), &d.step, step.min, step.max,
                         "%.2f", ImGuiSliderFlags_Logarithmic) &&
      d.step > 0.0f)
    viewer.set("step", format_number(d.step));
  if (enum_combo(std::string(key_label("noise_space")).c_str(), d.noise_space))
    viewer.apply_live(d);
  if (enum_combo(std::string(key_label("overlay")).c_str(), d.overlay)) viewer.apply_live(d);
  if (enum_combo("tangent", d.tangent)) {
    try {
      viewer.set_tangent(d.tangent);
    } catch (const std::exception& e) {
      viewer.message = std::string("error: ") + e.what();
    }
  }
  RenderSettings s = viewer.session().settings();
  if (s.use_color) {
    bool changed = enum_combo(std::string(key_label("color_map")).c_str(), d.color_map);
    if (ImGui::DragFloat2("colour range", &s.color_range.x, 0.01f) &&
        s.color_range.y > s.color_range.x) {
      d.color_range = ScalarRange{false, s.color_range.x, s.color_range.y};
      changed = true;
    }
    if (changed) viewer.apply_live(d);
  }
  if (s.use_beta && ImGui::DragFloat2("beta range", &s.beta_range.x, 0.01f) &&
      s.beta_range.y > s.beta_range.x) {
    d.beta_range = ScalarRange{false, s.beta_range.x, s.beta_range.y};
    viewer.apply_live(d);
  }
}

void ViewerPanel::draw_styles_and_files(ViewerSession& viewer) {
  int n = 0;
  for (const EnumName<Style>& style : enum_entries<Style>()) {
    const std::string name(style.name);
    if (n++ % 3 != 0) ImGui::SameLine();
    if (ImGui::Button(name.c_str())) viewer.apply_style(style.value);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", std::string(style.description).c_str());
  }
  char path[512];
  std::snprintf(path, sizeof path, "%s", load_path_.c_str());
  if (ImGui::InputText("mesh or scene", path, sizeof path)) load_path_ = path;
  if (ImGui::Button("load") && !load_path_.empty()) viewer.load(load_path_);
}

// Add, select, move (ctrl + drag on the surface) and shape flow elements.
void ViewerPanel::draw_elements(ViewerSession& viewer) {
  std::vector<FlowElement> elements = viewer.elements();
  bool changed = false;
  for (std::size_t i = 0; i < elements.size(); ++i) {
    char label[32];
    std::snprintf(label, sizeof label, "element %zu", i + 1);
    if (ImGui::RadioButton(label, viewer.selected_element == static_cast<int>(i)))
      viewer.selected_element = static_cast<int>(i);
  }
  if (ImGui::Button("add")) {
    // A vertical line through the look-at point, a fifth of the mesh long.
    const Bounds& b = viewer.camera().bounds();
    const glm::vec3 c = b.centre() + viewer.camera().params().target;
    const float half = 0.1f * b.diagonal();
    FlowElement e;
    e.a = c - glm::vec3(0, half, 0);
    e.b = c + glm::vec3(0, half, 0);
    e.rotational = 1.0f;
    elements.push_back(e);
    viewer.selected_element = static_cast<int>(elements.size()) - 1;
    changed = true;
  }
  ImGui::SameLine();
  if (ImGui::Button("remove") && viewer.selected_element >= 0 &&
      viewer.selected_element < static_cast<int>(elements.size())) {
    elements.erase(elements.begin() + viewer.selected_element);
    viewer.selected_element = -1;
    changed = true;
  }
  if (viewer.selected_element >= 0 && viewer.selected_element < static_cast<int>(elements.size())) {
    FlowElement& e = elements[static_cast<std::size_t>(viewer.selected_element)];
    changed |= ImGui::SliderFloat("rotational", &e.rotational, -2.0f, 2.0f);
    changed |= ImGui::SliderFloat("radial", &e.radial, -2.0f, 2.0f);
    changed |= ImGui::SliderFloat("tangential", &e.tangential, -2.0f, 2.0f);
    float length = glm::length(e.b - e.a);
    const float diagonal = viewer.camera().bounds().diagonal();
    if (ImGui::SliderFloat("length", &length, 0.01f * diagonal, 2.0f * diagonal)) {
      const glm::vec3 mid = 0.5f * (e.a + e.b), dir = glm::normalize(e.b - e.a);
      e.a = mid - 0.5f * length * dir;
      e.b = mid + 0.5f * length * dir;
      changed = true;
    }
    ImGui::TextUnformatted("ctrl + drag moves it along the surface");
  }
  if (changed) viewer.set_elements(std::move(elements));
}

}  // namespace ibfvs::app
