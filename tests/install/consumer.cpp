// Renders one IBFVS frame through the installed library: a typed scene,
// prepared, drawn by a session in a headless context.
#include <cstdio>

#include "ibfvs/core/scene/scene.h"
#include "ibfvs/core/scene/scene_prep.h"
#include "ibfvs/gl/context.h"
#include "ibfvs/render/session.h"
#ifdef CONSUMER_WITH_VTK
#include <fstream>

#include "ibfvs/core/mesh/dataset_io.h"
#include "ibfvs/vtk/vtk_io.h"
#endif

int main() {
  ibfvs::Scene scene;
  scene.mesh = "torus";
  scene.width = 96;
  scene.height = 64;
  ibfvs::apply_setting(scene, "field", "rotate:0,1,0");
  ibfvs::apply_setting(scene, "camera", "0,60,0");  // from above the ring
  ibfvs::gl::HeadlessContext context;
  ibfvs::Session session(ibfvs::prepare_scene(scene));
  for (int k = 0; k < 10; ++k) session.advance();
  const ibfvs::ImageU8 image = session.read_output();
  // The torus covers the middle of the image; the corners are background.
  const auto grey = [&](int x, int y) {
    const unsigned char* p = &image.pixels[(static_cast<std::size_t>(y) * image.width + x) * 4];
    return p[0] == p[1] && p[1] == p[2] && (p[0] == 127 || p[0] == 128);
  };
  int surface = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) surface += !grey(x, y);
  std::printf("consumer: %dx%d, %d surface pixels after %d frames on %s\n", image.width,
              image.height, surface, session.frame(), context.renderer().c_str());
  bool dataset_ok = true;
#ifdef CONSUMER_WITH_VTK
  ibfvs::vtk::install_vtk_io();
  std::ofstream("consumer.vtk")
      << "# vtk DataFile Version 4.2\nq\nASCII\nDATASET POLYDATA\n"
         "POINTS 4 float\n0 0 0 1 0 0 1 1 0 0 1 0\nPOLYGONS 1 5\n4 0 1 2 3\n";
  dataset_ok = ibfvs::read_dataset({"consumer.vtk", {}}).mesh.triangle_count() == 2;
  std::printf("consumer: read consumer.vtk through ibfvs::vtk: %s\n", dataset_ok ? "ok" : "wrong");
#endif
  return image.width == 96 && grey(0, 0) && surface > 2000 && dataset_ok ? 0 : 1;
}
