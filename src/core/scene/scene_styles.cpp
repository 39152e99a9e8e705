// The styles: the paper's looks as defaults of the keys (apply_style).
#include "ibfvs/core/scene/scene.h"

namespace ibfvs {

namespace {

// The bronze and eroded looks: colour by a curvature (p5 to p95), texture
// only where the surface is more concave than its median (to p98).
void curvature_look(Scene& s, const char* field, const char* curvature, ColorMap map) {
  s.default_field = FieldSpec::parse(field);
  s.color_by = curvature;
  s.color_map = map;
  s.color_range = ScalarRange{true, 5.0f, 95.0f};
  s.beta_by = std::string("-") + curvature;
  s.beta_range = ScalarRange{true, 50.0f, 98.0f};
  s.beta = 0.7f;
}

}  // namespace

void apply_style(Scene& s, Style style) {
  s.style = style;
  switch (style) {
    case Style::Flow:
      // Figures 1, 5: dense moving texture, beta 0.5, grey background.
      s.beta = 0.5f;
      s.background = glm::vec3(0.5f);
      break;
    case Style::Crisp:
      // docs/quality.md: longer unbroken lines than the defaults at about
      // 1.3 times their cost per pixel.
      s.filter = 24.0f;  // the defaults' 16 -> 24
      break;
    case Style::Paper:
      // Section 5's look, and Table 1's cost: 4-pixel noise cells, the
      // square profile at v_g 0.02, the flow's own speed, no display stage.
      s.scale = 4.0f;
      s.profile = NoiseProfile::Square;
      s.vg = 0.02f;
      s.beta = 0.5f;
      s.step = 3.0f;
      s.resample = Resample::Linear;
      s.image_normalize = false;
      s.filter = 0.0f;
      s.sharpen = 0.0f;
      s.contrast = 0.0f;
      break;
    case Style::Particles:
      // Figure 8a: short spikes so that few grid values are bright, added
      // rather than blended, along kappa_min where the mesh has no field.
      s.profile = NoiseProfile::Spike;
      s.spike_width = 0.04f;
      s.scale = 4.0f;  // one particle per 4 x 4 pixels, as the paper's
      s.inject = InjectMode::Add;
      s.contrast = 0.0f;  // sparse bright spikes on the dark: no stretch to mean 0.5
      s.filter = 0.0f;    // the comet tails as they are
      s.sharpen = 0.0f;
      s.image_normalize = false;  // faster particles where the flow is faster
      s.step = 3.0f;
      s.resample = Resample::Linear;
      s.alpha = 0.08f;
      s.background = {0.05f, 0.05f, 0.08f};
      s.beta = 0.7f;
      s.default_field = FieldSpec::parse("principal:min:smooth=10");
      break;
    case Style::Principal:
      // Figure 8b: dense texture along the principal directions, signed along
      // +Y (section 4.2's sign rule), smoothed over about three edges so that
      // scanned meshes give coherent strokes.
      s.default_field = FieldSpec::parse("principal:min:0,1,0:smooth=10");
      s.beta = 0.6f;
      break;
    case Style::Bronze:
      // Figure 9, "a dirty surface has superficially been cleaned": colour by
      // kappa_max (patina in the hollows, metal on the ridges) and the dirt
      // texture only in the more concave half (-kappa_max from its median to
      // its 98th percentile), so the rest shows clean metal.
      curvature_look(s, "principal:min:smooth=10", "kmax", ColorMap::Bronze);
      break;
    case Style::Eroded:
      // Eroded stone (section 4.2): the same, parametrised by kappa_min.
      curvature_look(s, "principal:max:smooth=10", "kmin", ColorMap::Grey);
      break;
    case Style::Topology:
      // Figure 7: alpha 0, random colours per noise cell, flow downhill along
      // the mesh's own height axis, seen from straight above it; locked once
      // the colours have had time to travel from the summits to the basin
      // borders, then seen obliquely.
      s.alpha = 0.0f;
      s.init = InitMode::RandomCells;
      s.contrast = 0.0f;  // colours, not a grey texture
      s.filter = 0.0f;
      s.sharpen = 0.0f;
      s.image_normalize = false;
      s.resample = Resample::Linear;
      s.step = 3.0f;
      s.default_field = FieldSpec::parse("gradient:down:normalize");
      s.up_auto = true;
      s.up.reset();
      s.camera.azimuth_deg = 0.0f;
      s.camera.elevation_deg = 90.0f;
      s.camera.distance = 0.0f;
      s.lock_at = Scene::kLockAuto;
      s.lock_camera = glm::vec3(20.0f, 35.0f, 0.0f);
      s.frames = 0;
      s.beta = 0.85f;
      s.scale = 6.0f;  // the colour cells, in pixels
      break;
  }
}

}  // namespace ibfvs
