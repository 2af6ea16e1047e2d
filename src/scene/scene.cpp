#include "scene/scene.h"

#include <algorithm>
#include <array>
#include <utility>

namespace whisker {

namespace {

// One table of names per enum: to_string and parse read the same one.
template <class E, std::size_t N>
using Names = std::array<std::pair<E, const char*>, N>;

constexpr Names<MaterialKind, 4> kMaterials{{{MaterialKind::Diffuse, "diffuse"},
                                             {MaterialKind::Mirror, "mirror"},
                                             {MaterialKind::Glass, "glass"},
                                             {MaterialKind::HollowGlass, "hollow_glass"}}};
constexpr Names<AccelKind, 4> kAccels{{{AccelKind::Brute, "brute"},
                                       {AccelKind::BBox, "bbox"},
                                       {AccelKind::Midpoint, "midpoint"},
                                       {AccelKind::Sah, "sah"}}};
constexpr Names<SamplerKind, 2> kSamplers{{{SamplerKind::Independent, "independent"},
                                           {SamplerKind::Sobol, "sobol"}}};

template <class E, std::size_t N>
const char* name_of(const Names<E, N>& names, E e) {
  for (const auto& [k, n] : names)
    if (k == e) return n;
  return "?";
}

template <class E, std::size_t N>
bool value_of(const Names<E, N>& names, std::string_view s, E& out) {
  for (const auto& [k, n] : names)
    if (s == n) {
      out = k;
      return true;
    }
  return false;
}

}  // namespace

const char* to_string(MaterialKind k) { return name_of(kMaterials, k); }
const char* to_string(AccelKind k) { return name_of(kAccels, k); }
const char* to_string(SamplerKind k) { return name_of(kSamplers, k); }
bool parse(std::string_view s, MaterialKind& out) { return value_of(kMaterials, s, out); }
bool parse(std::string_view s, AccelKind& out) { return value_of(kAccels, s, out); }
bool parse(std::string_view s, SamplerKind& out) { return value_of(kSamplers, s, out); }

std::string check_split(const std::vector<int>& split) {
  if (split.empty()) return "must hold at least one factor";
  if (split.size() > std::size_t(kMaxSplitLevels))
    return "at most " + std::to_string(kMaxSplitLevels) + " factors, got " +
           std::to_string(split.size());
  long long paths = 1;
  for (int k : split) {
    if (k < 1 || k > kMaxSplitFactor)
      return "factors must be in [1, " + std::to_string(kMaxSplitFactor) + "], got " +
             std::to_string(k);
    paths *= k;
  }
  if (paths > kMaxSplitPaths)
    return "the factors' product (paths per sample) must be at most " +
           std::to_string(kMaxSplitPaths) + ", got " + std::to_string(paths);
  return {};
}

std::string split_to_string(const std::vector<int>& split) {
  std::string s;
  for (int k : split) {
    if (!s.empty()) s += ',';
    s += std::to_string(k);
  }
  return s;
}

}  // namespace whisker
