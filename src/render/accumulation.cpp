#include "render/accumulation.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <sstream>

#include <nlohmann/json.hpp>

#include "geometry/mesh.h"
#include "scene/scene_io.h"
#include "scene/settings_json.h"

namespace whisker {

using nlohmann::json;

namespace {

// FNV-1a, 64 bits (Fowler, Noll, Vo): a fingerprint, not a defence.
struct Fnv1a {
  std::uint64_t h = 0xcbf29ce484222325ull;
  void add(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
  }
  template <class T>
  void add_vector(const std::vector<T>& v) {
    add(v.data(), v.size() * sizeof(T));
  }
  std::string hex() const {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    return buf;
  }
};

bool parse_u64(std::string_view s, std::uint64_t& out) {
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && end == s.data() + s.size() && !s.empty();
}

std::string size_text(const Accumulation& a) {
  return std::to_string(a.width) + "x" + std::to_string(a.height);
}

}  // namespace

bool parse_sample_range(const std::string& text, SampleRange& out) {
  const auto colon = text.find(':');
  if (colon == std::string::npos) return false;
  SampleRange r;
  if (!parse_u64(std::string_view(text).substr(0, colon), r.begin) ||
      !parse_u64(std::string_view(text).substr(colon + 1), r.end) || r.begin >= r.end)
    return false;
  out = r;
  return true;
}

std::string ranges_to_string(const std::vector<SampleRange>& ranges) {
  std::string s;
  for (const SampleRange& r : ranges) {
    if (!s.empty()) s += ',';
    s += std::to_string(r.begin);
    s += ':';
    s += std::to_string(r.end);
  }
  return s;
}

bool parse_ranges(const std::string& text, std::vector<SampleRange>& out) {
  std::vector<SampleRange> ranges;
  // getline drops a trailing empty item: "0:5," would read as "0:5".
  if (!text.empty() && text.back() == ',') return false;
  std::istringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    SampleRange r;
    if (!parse_sample_range(item, r)) return false;
    if (!ranges.empty() && r.begin < ranges.back().end) return false;
    ranges.push_back(r);
  }
  if (ranges.empty()) return false;
  out = ranges;
  return true;
}

// The project version, from CMake (CMakeLists.txt, whisker_render).
#ifndef WHISKER_PROJECT_VERSION
#error "WHISKER_PROJECT_VERSION must be defined (the project version, from CMake)"
#endif

std::string estimator_identity() {
  return "whisker " WHISKER_PROJECT_VERSION " estimator " + std::to_string(kEstimatorRevision);
}

RenderIdentity render_identity(const Scene& scene) {
  RenderIdentity id;
  id.estimator = estimator_identity();
  id.scene = scene.name;
  // The scene as its file would say it (camera, light, objects), without the
  // settings, and the triangles its meshes loaded to.
  json j = scene_json(scene);
  j.erase("settings");
  Fnv1a h;
  const std::string text = j.dump(-1, ' ', false, json::error_handler_t::replace);
  h.add(text.data(), text.size());
  for (const MeshObject& m : scene.meshes) {
    if (!m.mesh) continue;
    h.add_vector(m.mesh->positions);
    h.add_vector(m.mesh->triangles);
    h.add_vector(m.mesh->normals);
    h.add_vector(m.mesh->normal_idx);
  }
  id.scene_hash = h.hex();
  json s = settings_to_json(scene.settings);
  s.erase("spp");  // passes' size: the samples are the same whatever it is
  s.erase("target_spp");
  id.settings = s.dump();
  return id;
}

std::uint64_t Accumulation::samples() const {
  std::uint64_t n = 0;
  for (const SampleRange& r : ranges) n += r.end - r.begin;
  return n;
}

Accumulation accumulation_of(const Snapshot& snap, std::uint64_t first_sample,
                             const RenderIdentity& id) {
  Accumulation a;
  a.width = snap.width;
  a.height = snap.height;
  a.sum = snap.sum;
  a.sum_sq = snap.sum_sq;
  const std::size_t pixels = std::size_t(snap.width) * std::size_t(snap.height);
  if (snap.features.size() == pixels * kFeatureSums && snap.odd_rgb.size() == pixels * 3) {
    a.with_features = true;
    a.odd_rgb = snap.odd_rgb;
    a.features = snap.features;
  }
  if (snap.spp > 0) a.ranges = {{first_sample, first_sample + snap.spp}};
  a.counters = snap.counters;
  a.id = id;
  return a;
}

Snapshot snapshot_of(const Accumulation& acc) {
  Accumulation copy = acc;
  return snapshot_of(std::move(copy));
}

Snapshot snapshot_of(Accumulation&& acc) {
  Snapshot s;
  s.width = acc.width;
  s.height = acc.height;
  s.spp = acc.samples();
  // Where the samples start: which of them are odd (the half images).
  s.first_sample = acc.ranges.empty() ? 0 : acc.ranges.front().begin;
  s.counters = acc.counters;
  s.done = true;
  s.sum = std::move(acc.sum);
  s.sum_sq = std::move(acc.sum_sq);
  if (acc.with_features) {
    s.odd_rgb = std::move(acc.odd_rgb);
    s.features = std::move(acc.features);
  }
  return s;
}

std::string identity_mismatch(const Accumulation& a, const Accumulation& b) {
  if (a.width != b.width || a.height != b.height) return "size: " + size_text(a) + " vs " + size_text(b);
  if (a.id.scene != b.id.scene) return "scene: \"" + a.id.scene + "\" vs \"" + b.id.scene + "\"";
  if (a.id.estimator != b.id.estimator)
    return "estimator: \"" + a.id.estimator + "\" vs \"" + b.id.estimator + "\" (another build)";
  if (a.id.scene_hash != b.id.scene_hash)
    return "scene file or meshes (hash " + a.id.scene_hash + " vs " + b.id.scene_hash + ")";
  if (a.id.settings == b.id.settings) return {};
  // Name the first setting that differs.
  const json sa = json::parse(a.id.settings, nullptr, false);
  const json sb = json::parse(b.id.settings, nullptr, false);
  if (sa.is_object() && sb.is_object())
    for (const auto& [key, value] : sa.items())
      if (!sb.contains(key) || sb[key] != value)
        return "settings." + key + ": " + value.dump() + " vs " +
               (sb.contains(key) ? sb[key].dump() : std::string("(missing)"));
  return "settings: " + a.id.settings + " vs " + b.id.settings;
}

std::string mixed_features(const std::vector<NamedAccumulation>& parts) {
  const NamedAccumulation* with = nullptr;
  const NamedAccumulation* without = nullptr;
  for (const NamedAccumulation& p : parts) (p.acc.with_features ? with : without) = &p;
  if (!with || !without) return {};
  return without->name + " keeps no feature buffers (" + with->name + " does)";
}

Accumulation plan_merge(const std::vector<NamedAccumulation>& parts, std::vector<std::size_t>& order) {
  if (parts.empty()) throw AccumulationError("nothing to merge");
  for (std::size_t i = 1; i < parts.size(); ++i) {
    const Accumulation &a = parts[0].acc, &b = parts[i].acc;
    if (a.width != b.width || a.height != b.height)
      throw AccumulationError("part " + parts[i].name + " is " + size_text(b) + ", part " +
                              parts[0].name + " is " + size_text(a) +
                              " (the parts of one render have its size)");
    if (const std::string why = identity_mismatch(parts[0].acc, parts[i].acc); !why.empty())
      throw AccumulationError(parts[0].name + " and " + parts[i].name + " differ in " + why);
  }
  // Every range with its file, in sample order; neighbours must not overlap.
  struct Owned {
    SampleRange r;
    const std::string* name;
  };
  std::vector<Owned> all;
  for (const auto& p : parts) {
    if (p.acc.ranges.empty()) throw AccumulationError(p.name + ": holds no samples");
    for (const SampleRange& r : p.acc.ranges) all.push_back({r, &p.name});
  }
  std::sort(all.begin(), all.end(), [](const Owned& x, const Owned& y) { return x.r.begin < y.r.begin; });
  for (std::size_t i = 1; i < all.size(); ++i)
    if (all[i].r.begin < all[i - 1].r.end)
      throw AccumulationError("samples " + ranges_to_string({all[i - 1].r}) + " of " +
                              *all[i - 1].name + " overlap samples " +
                              ranges_to_string({all[i].r}) + " of " + *all[i].name);
  // Fold in range order (the exactness rule in the header).
  order.resize(parts.size());
  for (std::size_t i = 0; i < parts.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
    return parts[x].acc.ranges.front().begin < parts[y].acc.ranges.front().begin;
  });
  Accumulation out;
  out.width = parts[0].acc.width;
  out.height = parts[0].acc.height;
  out.id = parts[0].acc.id;
  out.with_features = mixed_features(parts).empty() && parts[0].acc.with_features;
  for (const auto& p : parts) out.counters += p.acc.counters;
  // The union of the ranges, touching ones joined.
  for (const Owned& o : all) {
    if (!out.ranges.empty() && out.ranges.back().end == o.r.begin)
      out.ranges.back().end = o.r.end;
    else
      out.ranges.push_back(o.r);
  }
  return out;
}

namespace {

// to[k] += from[k] for k < n: the one addition of every fold.
void add_to(std::vector<double>& to, std::size_t at, const double* from, std::size_t n) {
  double* t = to.data() + at;
  for (std::size_t k = 0; k < n; ++k) t[k] += from[k];
}

}  // namespace

void add_sums(Accumulation& into, const SumsBand& band) {
  const std::size_t all = std::size_t(into.width) * std::size_t(into.height);
  if (into.sum.empty()) {  // the first part: the fold starts from zero
    into.sum.assign(all * 3, 0.0);
    into.sum_sq.assign(all, 0.0);
    into.odd_rgb.assign(into.with_features ? all * 3 : 0, 0.0);
    into.features.assign(into.with_features ? all * kFeatureSums : 0, 0.0);
  }
  if (band.first > all || band.pixels > all - band.first)
    throw AccumulationError("a part's sums are not of the merge's size");
  add_to(into.sum, band.first * 3, band.sum, band.pixels * 3);
  add_to(into.sum_sq, band.first, band.sum_sq, band.pixels);
  if (!into.with_features) return;
  if (!band.odd_rgb || !band.features) throw AccumulationError("a part keeps no feature buffers");
  add_to(into.odd_rgb, band.first * 3, band.odd_rgb, band.pixels * 3);
  add_to(into.features, band.first * kFeatureSums, band.features, band.pixels * kFeatureSums);
}

void add_sums(Accumulation& into, const Accumulation& part) {
  const std::size_t pixels = std::size_t(into.width) * std::size_t(into.height);
  if (part.sum.size() != pixels * 3 || part.sum_sq.size() != pixels)
    throw AccumulationError("a part's sums are not of the merge's size");
  const bool features = part.odd_rgb.size() == pixels * 3 && part.features.size() == pixels * kFeatureSums;
  add_sums(into, {0, pixels, part.sum.data(), part.sum_sq.data(), features ? part.odd_rgb.data() : nullptr,
                  features ? part.features.data() : nullptr});
}

Accumulation merge_accumulations(std::vector<NamedAccumulation> parts) {
  std::vector<std::size_t> order;
  Accumulation out = plan_merge(parts, order);
  for (const std::size_t i : order) add_sums(out, parts[i].acc);
  return out;
}

std::vector<SampleRange> missing_ranges(const std::vector<SampleRange>& ranges) {
  std::vector<SampleRange> gaps;
  std::uint64_t at = 0;
  for (const SampleRange& r : ranges) {
    if (r.begin > at) gaps.push_back({at, r.begin});
    at = std::max(at, r.end);
  }
  return gaps;
}

}  // namespace whisker
