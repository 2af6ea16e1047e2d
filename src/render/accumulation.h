// Accumulations: a render's un-normalised double sums with the sample ranges
// they hold and what they were rendered from, so that parts rendered apart
// (sample-range shards, an interrupted render) merge and resume exactly.
//
// Exactness rule: the film adds each pass's per-pixel sum (computed from zero
// in sample order) into its double buffer. A merge folds the parts' sums in
// the order of their ranges, starting from zero. So the merge of parts equals
// bit for bit the single render whose passes are those parts: `0:512` and
// `512:1024` rendered as one pass each merge to the render of `0:1024` in two
// passes of 512. (A part that holds several passes is exact as the first
// part; after it, use one pass per part.)
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/film.h"
#include "scene/scene.h"

namespace whisker {

// Sample indices [begin, end) of every pixel.
struct SampleRange {
  std::uint64_t begin = 0, end = 0;
  bool operator==(const SampleRange&) const = default;
};

// "0:512" -> {0, 512}; false if malformed or empty (begin >= end).
bool parse_sample_range(const std::string& text, SampleRange& out);
// "0:512,1024:2048".
std::string ranges_to_string(const std::vector<SampleRange>& ranges);
// Parses ranges_to_string's output; false if malformed.
bool parse_ranges(const std::string& text, std::vector<SampleRange>& out);

// The estimator's revision: BUMP IT with every change to what a render's
// samples are (the estimator, integrator, path reuse, light connections,
// splitting, scattering, sampler, camera, film: anything in src/render, or
// the scene's compiled world, that changes a pixel's sum). A part carries
// it (with the project version) so that parts rendered by estimators that
// differ never merge or resume into one another.
inline constexpr int kEstimatorRevision = 1;
// "whisker 0.1.0 estimator 1": the project version and kEstimatorRevision.
std::string estimator_identity();

// What a render is of: parts merge only if all four agree.
struct RenderIdentity {
  std::string scene;       // the scene's name
  std::string scene_hash;  // FNV-1a of the scene without settings, and its meshes
  std::string settings;    // the settings as JSON, without spp and target_spp
  std::string estimator;   // estimator_identity() of the build that rendered it
};
// The identity of rendering `scene` with this build (spp and target_spp only
// shape passes).
RenderIdentity render_identity(const Scene& scene);

struct Accumulation {
  int width = 0, height = 0;
  std::vector<double> sum;     // RGB sums, width*height*3, row 0 = top
  std::vector<double> sum_sq;  // luminance sums of squares, width*height
  // With the denoiser's feature buffers (Snapshot::odd_rgb and features,
  // summed over the same samples as `sum`, in the same order); a header
  // read alone says so with the sums empty. Without: false, both empty.
  bool with_features = false;
  std::vector<double> odd_rgb;   // 3 a pixel
  std::vector<double> features;  // kFeatureSums a pixel
  std::vector<SampleRange> ranges;  // sorted and disjoint
  RenderCounters counters;          // summed over parts
  RenderIdentity id;

  std::uint64_t samples() const;  // per pixel: the ranges' total length
};

struct AccumulationError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The accumulation of a snapshot whose samples start at `first_sample`.
Accumulation accumulation_of(const Snapshot& snap, std::uint64_t first_sample,
                             const RenderIdentity& id);
// A snapshot of an accumulation, so mean_image, the stats and the denoiser
// see it as they see a render (its feature sums, and its first sample,
// which says which samples are odd). The second takes the sums over instead of copying them.
Snapshot snapshot_of(const Accumulation& acc);
Snapshot snapshot_of(Accumulation&& acc);

// The first field in which a and b differ ("size", "scene", "estimator",
// "scene file or meshes", "settings.seed", ...) with both values, or "" if
// they agree. The size comes first: it is also in the scene file's hash.
std::string identity_mismatch(const Accumulation& a, const Accumulation& b);

// A part to merge and the file it came from (for messages).
struct NamedAccumulation {
  std::string name;
  Accumulation acc;
};
// "" if every part keeps feature buffers or none does; else a line naming a
// part with them and one without (a merge of both keeps none).
std::string mixed_features(const std::vector<NamedAccumulation>& parts);
// Folds the parts' sums in the order of their ranges (their features too
// when every part has them). Throws
// AccumulationError naming the files and the differing field, or the two
// overlapping ranges.
Accumulation merge_accumulations(std::vector<NamedAccumulation> parts);
// The same in steps, so that a merge holds a band of one part's sums at a
// time: plan_merge checks the parts' headers (their sums may be empty) and
// returns the merged header with empty sums, and in `order` the order to add
// the parts' sums in with add_sums (from zero, as merge_accumulations does).
// The merged header keeps features when every part has them.
Accumulation plan_merge(const std::vector<NamedAccumulation>& parts, std::vector<std::size_t>& order);
void add_sums(Accumulation& into, const Accumulation& part);
// The sums of `pixels` pixels from pixel `first` on (row-major): 3 a pixel
// in `sum` and `odd_rgb`, one in `sum_sq`, kFeatureSums in `features`
// (odd_rgb and features null for a part without feature buffers).
struct SumsBand {
  std::size_t first = 0, pixels = 0;
  const double* sum = nullptr;
  const double* sum_sq = nullptr;
  const double* odd_rgb = nullptr;
  const double* features = nullptr;
};
// Adds a band. Each element's addition is the one add_sums makes, so adding
// a part band by band gives the same bits. The features are added when
// `into` keeps them (the band must then have them).
void add_sums(Accumulation& into, const SumsBand& band);
// The ranges missing from [0, last end): the gaps between `ranges`.
std::vector<SampleRange> missing_ranges(const std::vector<SampleRange>& ranges);

}  // namespace whisker
