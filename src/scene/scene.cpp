#include "scene/scene.h"

#include <algorithm>

namespace whisker {

namespace {
constexpr EnumName<MaterialKind> kMaterials[] = {{MaterialKind::Diffuse, "diffuse"},
                                                 {MaterialKind::Mirror, "mirror"},
                                                 {MaterialKind::Glass, "glass"},
                                                 {MaterialKind::HollowGlass, "hollow_glass"}};
}  // namespace

std::span<const EnumName<MaterialKind>> enum_names(MaterialKind) { return kMaterials; }

}  // namespace whisker
