#include "app/denoised_output.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "render/film_denoise.h"
#include "scene/file_name.h"
#include "scene/quote.h"

namespace whisker {

namespace {

// The scales the denoised image's error is estimated at (box filters, px).
constexpr int kDenoiseScales[] = {1, 2, 4, 8, 16};

// The error estimate of `r` at each scale into `rec`, and the summary line.
void report_estimate(const DenoisedOutput& out, const DenoiseInput& in, const DenoiseResult& r,
                     nlohmann::json& rec) {
  const char* filter = out.fast ? "fast" : "quality";
  // Mean squared error per block and channel against the true image, in
  // the image's units, both from the two half images (render/denoise.h).
  // The estimate needs independent halves: Sobol points of even and odd
  // index are stratified together (their difference overstates the noise,
  // and the estimate reads near zero), independent numbers are not.
  rec["estimate_valid"] = out.independent;
  if (!out.independent)
    rec["estimate_note"] = "the Sobol sampler's even and odd samples are not independent halves; "
                           "render with --sampler independent for an estimate";
  std::string line;
  for (const int k : kDenoiseScales) {
    if (k > std::min(in.width, in.height)) break;
    const ScaleError e = estimate_error(in, r, k);
    rec["estimated_mse"].push_back({{"scale_px", k},
                                    {"raw", e.raw_mse},
                                    {"denoised", e.denoised_mse},
                                    {"denoised_bias2", e.denoised_bias2},
                                    {"denoised_better", e.denoised_better()}});
    char part[64];
    std::snprintf(part, sizeof part, " %d px %.2g", k, e.raw_mse > 0 ? e.denoised_mse / e.raw_mse : 0.0);
    line += part;
  }
  if (out.independent)
    std::printf("denoised (%s filter): estimated error over the raw image's,%s -> %s\n", filter,
                line.c_str(), printable(out.path).c_str());
  else
    std::printf("denoised (%s filter), no error estimate (Sobol halves are not independent; "
                "--sampler independent gives one) -> %s\n",
                filter, printable(out.path).c_str());
}

}  // namespace

std::string write_denoised(const DenoisedOutput& out, const Snapshot& snap, const Image& raw) {
  nlohmann::json rec = {{"file", out.path}};
  Image img = raw;
  const auto t0 = std::chrono::steady_clock::now();
  if (out.exact) {
    rec["filter"] = "none: the estimate is exact";
  } else {
    FilmHalves halves;
    if (const std::string why = film_halves(snap, halves); !why.empty())
      throw ImageError("--out-denoised " + printable(out.path) + ": " + why);
    const DenoiseInput in = halves.input();
    const DenoiseResult r = denoise(in, {out.fast ? DenoiseFilter::Fast : DenoiseFilter::Quality, out.threads});
    img.rgb = r.rgb;
    rec["filter"] = out.fast ? "fast" : "quality";
    rec["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    report_estimate(out, in, r, rec);
  }
  if (lower_extension(out.path) == ".png") {
    write_png(out.path, img);
  } else {
    ImageAttributes a = out.attributes;
    a.emplace_back("whisker.image", std::string("denoised (") + rec["filter"].get<std::string>() +
                                        "), not the raw estimate; the stats give its estimated error");
    write_float_image(out.path, out.display_units ? display_referred(img) : img, a);
  }
  return rec.dump();
}

ImageLayers feature_layers(const Snapshot& snap, bool display_units) {
  FilmHalves h;
  if (!film_halves(snap, h).empty()) return {};
  const float scale = display_units ? 1.0f / report_white() : 1.0f;
  const std::size_t pixels = std::size_t(h.width) * std::size_t(h.height);
  ImageLayers layers;
  // One layer of channel c of a buffer holding `n` floats a pixel.
  const auto add = [&](const std::string& name, const std::vector<float>& buffer, int n, int c, float times) {
    ImageLayer l{name, std::vector<float>(pixels)};
    for (std::size_t p = 0; p < pixels; ++p) l.values[p] = buffer[p * std::size_t(n) + std::size_t(c)] * times;
    layers.push_back(std::move(l));
  };
  for (int half = 0; half < 2; ++half) {
    const std::string prefix = half == 0 ? "even." : "odd.";
    for (int c = 0; c < 3; ++c) {
      add(prefix + "RGB"[c], h.colour[half], 3, c, scale);
      add(prefix + "albedo." + "RGB"[c], h.albedo[half], 3, c, 1.0f);
      add(prefix + "normal." + "XYZ"[c], h.normal[half], 3, c, 1.0f);
    }
    add(prefix + "depth.Z", h.depth[half], 1, 0, 1.0f);
  }
  return layers;
}

void add_feature_note(ImageAttributes& attributes) {
  attributes.emplace_back(
      "whisker.features",
      "the denoiser's inputs as layers: even.* the mean of the even-indexed samples, odd.* of the odd "
      "ones; each R, G, B (as the image's units), albedo.R, G, B, normal.X, Y, Z (world space) and "
      "depth.Z (of the first non-specular hit; 1e9 for a miss)");
}

}  // namespace whisker
