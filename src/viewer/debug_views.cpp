#include "viewer/debug_views.h"

#include <algorithm>
#include <cstdio>
#include <vector>

#include "scene/world.h"
#include "render/camera.h"

namespace whisker {

DebugImage render_debug_view(const Scene& scene, int view) {
  DebugImage d;
  d.view = view;
  const int w = scene.camera.width, h = scene.camera.height;
  Snapshot& s = d.image;
  s.width = w;
  s.height = h;
  s.spp = 1;
  s.sum.assign(std::size_t(w) * h * 3, 0.0);
  s.sum_sq.assign(std::size_t(w) * h, 0.0);
  if (w <= 0 || h <= 0) return d;
  const World world(scene);
  const CameraFrame cam(scene.camera);
  std::vector<float> depth(std::size_t(w) * h, -1.0f);
  for (int i = 0; i < h; ++i) {
    for (int j = 0; j < w; ++j) {
      SurfaceHit hit;
      if (!world.intersect(world.to_render(cam.origin, cam.centre_direction(i, j)), hit)) continue;
      const std::size_t p = std::size_t(i) * w + j;
      vec3 c(0.0f);
      if (view == kViewNormals) {
        c = hit.ns * 0.5f + vec3(0.5f);
      } else if (view == kViewAlbedo && hit.material) {
        const MaterialKind k = hit.material->kind;
        c = k == MaterialKind::Diffuse ? hit.material->albedo
            : k == MaterialKind::Mirror ? vec3(kMirrorGrey)
                                        : kGlassColour;
      }
      depth[p] = hit.t;
      d.far = std::max(d.far, hit.t);
      for (int ch = 0; ch < 3; ++ch) s.sum[3 * p + ch] = std::clamp(c[ch], 0.0f, 1.0f);
    }
  }
  if (view == kViewDepth && d.far > 0.0f)
    for (std::size_t p = 0; p < depth.size(); ++p)
      if (depth[p] >= 0.0f)
        s.sum[3 * p] = s.sum[3 * p + 1] = s.sum[3 * p + 2] = 1.0f - depth[p] / d.far;
  return d;
}

std::string debug_legend(const DebugImage& d) {
  char buf[128];
  switch (d.view) {
    case kViewNormals:
      return "normals: x red, y green, z blue (n/2 + 1/2)";
    case kViewAlbedo:
      return "material: diffuse albedo; mirror grey; glass light blue";
    case kViewDepth:
      std::snprintf(buf, sizeof buf, "depth: white near, black at %.3g units", double(d.far));
      return buf;
    default:
      return {};
  }
}

}  // namespace whisker
