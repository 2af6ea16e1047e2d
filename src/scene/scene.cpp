#include "scene/scene.h"

#include <algorithm>

namespace whisker {

int weighted_split(int split, const vec3& beta, const vec3& weights) {
  float w = 0.0f;
  for (int c = 0; c < 3; ++c)
    if (beta[c] != 0.0f) w = std::max(w, weights[c]);
  return std::max(1, int(float(split) * w + 0.5f));
}

namespace {
constexpr EnumName<MaterialKind> kMaterials[] = {{MaterialKind::Diffuse, "diffuse"},
                                                 {MaterialKind::Mirror, "mirror"},
                                                 {MaterialKind::Glass, "glass"},
                                                 {MaterialKind::HollowGlass, "hollow_glass"}};
}  // namespace

std::span<const EnumName<MaterialKind>> enum_names(MaterialKind) { return kMaterials; }

}  // namespace whisker
