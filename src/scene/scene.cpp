#include "scene/scene.h"

namespace whisker {

const char* to_string(MaterialKind k) {
  switch (k) {
    case MaterialKind::Diffuse: return "diffuse";
    case MaterialKind::Mirror: return "mirror";
    case MaterialKind::Glass: return "glass";
    case MaterialKind::HollowGlass: return "hollow_glass";
  }
  return "?";
}

const char* to_string(AccelKind k) {
  switch (k) {
    case AccelKind::Brute: return "brute";
    case AccelKind::BBox: return "bbox";
    case AccelKind::Midpoint: return "midpoint";
    case AccelKind::Sah: return "sah";
  }
  return "?";
}

const char* to_string(SamplerKind k) {
  return k == SamplerKind::Independent ? "independent" : "sobol";
}

}  // namespace whisker
