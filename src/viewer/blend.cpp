#include "viewer/blend.h"

#include <algorithm>

namespace whisker {

double own_sample_weight(const RenderSettings& s) {
  if (!s.indirect) return 1.0;  // the same estimator, several samples a pass
  double paths = 1.0;
  for (int f : s.split) paths *= double(std::max(1, f));
  return paths;
}

void blend_for_display(const Snapshot& own, const Snapshot& quick, const RenderSettings& own_settings,
                       Shown& out) {
  const bool have_quick = quick.spp > 0 && quick.width == own.width && quick.height == own.height;
  if (quick.spp > 0 && (own.spp == 0 || quick.generation > own.generation)) {
    out.image = quick;  // the edit's first images, before its own first pass
    out.quick_spp = quick.spp;
    out.own_spp = 0;
    return;
  }
  const double w_own = double(own.spp) * own_sample_weight(own_settings);
  const double w_quick = double(quick.spp);
  if (!have_quick || quick.generation != own.generation || w_own >= kDropQuickRatio * w_quick) {
    out.image = own;
    out.quick_spp = 0;
    out.own_spp = own.spp;
    return;
  }
  // mean = (w_own * own_mean + w_quick * quick_mean) / (w_own + w_quick),
  // stored as a sum over own.spp samples so that sum / spp is that mean.
  out.image = own;
  const double a = w_own / (w_own + w_quick) / double(own.spp) * double(own.spp);
  const double b = w_quick / (w_own + w_quick) / double(quick.spp) * double(own.spp);
  for (std::size_t k = 0; k < out.image.sum.size(); ++k)
    out.image.sum[k] = a * own.sum[k] + b * quick.sum[k];
  out.quick_spp = quick.spp;
  out.own_spp = own.spp;
}

}  // namespace whisker
