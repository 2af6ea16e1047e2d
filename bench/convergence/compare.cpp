// whisker-compare: how far a rendered image is from a reference.
//
//   whisker-compare IMAGE.pfm REFERENCE.pfm [--white W] [--json OUT.json]
//
// Both images are linear radiance (the light intensity applied), as written
// by `whisker --out-float x.pfm`. Every value is first divided by W, by
// default 255^2.2 = 196964.7: the radiance the report's display mapping
// min(255, L^(1/2.2)) shows as white. So 1.0 is display white, the metrics
// read the same whatever the light intensity, and the 0.01 in relMSE has its
// usual meaning (a tenth of white) instead of vanishing next to radiances of
// 1e5. `--white 1` gives raw radiance units. Over the N = width x height x 3
// values x_i of IMAGE and r_i of REFERENCE so scaled:
//
//   MSE      = 1/N sum (x_i - r_i)^2
//   RMSE     = sqrt(MSE)
//   relMSE   = 1/N sum (x_i - r_i)^2 / (r_i^2 + 0.01)
//
// and, to tell noise from bias when comparing two converged images, the
// signed mean difference per pixel d_p = mean over channels of (x - r), its
// mean over pixels and that mean divided by its standard error
// (sd(d_p) / sqrt(pixels)); pixels are rendered independently, so for two
// unbiased estimators of the same image |z| stays within a few units.
//
// At coarser scales (--scales 1,2,4,8,16, the default): both images are
// box-filtered by k (the mean of each k x k block; blocks past the edge
// dropped) before the MSE, so `mse_by_scale` says how large the error is
// that a person sees from further away. For independent pixel errors the
// MSE at scale k is the pixel MSE / k^2; correlated errors (blotches) fall
// slower, anticorrelated ones (blue noise) faster.
//
// Prints one line of text; with --json also writes the figures as JSON.
// Exit code 2 on bad input (missing file, size mismatch).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/image_io.h"

namespace {

struct Metrics {
  int width = 0, height = 0;
  double mse = 0, rmse = 0, rel_mse = 0;
  double mean_image = 0, mean_reference = 0;
  double mean_diff = 0, mean_diff_z = 0;
  long long nonfinite = 0;
};

Metrics compare(const whisker::Image& x, const whisker::Image& r, double white) {
  Metrics m;
  m.width = x.width;
  m.height = x.height;
  const std::size_t pixels = std::size_t(x.width) * x.height;
  // Sums in double: at up to 512x512x3 values nothing is lost that matters.
  double se = 0, rel = 0, sx = 0, sr = 0, sd = 0, sd2 = 0;
  for (std::size_t p = 0; p < pixels; ++p) {
    double d_pixel = 0;
    for (int c = 0; c < 3; ++c) {
      const double xi = x.rgb[3 * p + c] / white, ri = r.rgb[3 * p + c] / white;
      if (!std::isfinite(xi) || !std::isfinite(ri)) {
        ++m.nonfinite;
        continue;
      }
      const double d = xi - ri;
      se += d * d;
      rel += d * d / (ri * ri + 0.01);
      sx += xi;
      sr += ri;
      d_pixel += d / 3.0;
    }
    sd += d_pixel;
    sd2 += d_pixel * d_pixel;
  }
  const double n = double(pixels) * 3.0;
  m.mse = se / n;
  m.rmse = std::sqrt(m.mse);
  m.rel_mse = rel / n;
  m.mean_image = sx / n;
  m.mean_reference = sr / n;
  const double np = double(pixels);
  m.mean_diff = sd / np;
  const double var = np > 1 ? (sd2 - sd * sd / np) / (np - 1) : 0.0;
  const double se_mean = std::sqrt(std::max(var, 0.0) / np);
  m.mean_diff_z = se_mean > 0 ? m.mean_diff / se_mean : 0.0;
  return m;
}

// MSE between x and r after both are box-filtered by k (white-scaled),
// over the finite blocks.
double mse_at_scale(const whisker::Image& x, const whisker::Image& r, double white, int k) {
  const int bw = x.width / k, bh = x.height / k;
  double se = 0;
  long long n = 0;
  for (int by = 0; by < bh; ++by)
    for (int bx = 0; bx < bw; ++bx)
      for (int c = 0; c < 3; ++c) {
        double d = 0;
        for (int y = by * k; y < (by + 1) * k; ++y)
          for (int xx = bx * k; xx < (bx + 1) * k; ++xx) {
            const std::size_t i = (std::size_t(y) * x.width + xx) * 3 + c;
            d += (double(x.rgb[i]) - double(r.rgb[i])) / white;
          }
        d /= double(k) * k;
        if (!std::isfinite(d)) continue;
        se += d * d;
        ++n;
      }
  return n ? se / double(n) : NAN;
}

// "1,2,4" -> {1, 2, 4}; empty on a malformed list.
std::vector<int> parse_scales(const char* text) {
  std::vector<int> out;
  const char* p = text;
  while (*p) {
    char* end = nullptr;
    const long k = std::strtol(p, &end, 10);
    if (end == p || k < 1 || k > 4096) return {};
    out.push_back(int(k));
    p = end;
    if (*p == ',') {
      if (!*++p) return {};
    } else if (*p) {
      return {};
    }
  }
  return out;
}

int usage() {
  std::fprintf(stderr, "usage: whisker-compare IMAGE.pfm REFERENCE.pfm [--white W] [--scales 1,2,4,8,16] [--json OUT.json]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string image_path, ref_path, json_path;
  double white = std::pow(255.0, 2.2);
  std::vector<int> scales = {1, 2, 4, 8, 16};
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--json") == 0) {
      if (++i >= argc) return usage();
      json_path = argv[i];
    } else if (std::strcmp(argv[i], "--scales") == 0) {
      if (++i >= argc) return usage();
      scales = parse_scales(argv[i]);
      if (scales.empty()) {
        std::fprintf(stderr, "whisker-compare: --scales %s: need box sizes like 1,2,4,8,16\n", argv[i]);
        return 2;
      }
    } else if (std::strcmp(argv[i], "--white") == 0) {
      if (++i >= argc) return usage();
      char* end = nullptr;
      white = std::strtod(argv[i], &end);
      if (end == argv[i] || *end != '\0' || !(white > 0) || !std::isfinite(white)) {
        std::fprintf(stderr, "whisker-compare: --white %s: need a positive number\n", argv[i]);
        return 2;
      }
    } else if (argv[i][0] == '-' && argv[i][1] != '\0') {
      std::fprintf(stderr, "whisker-compare: unknown option %s\n", argv[i]);
      return usage();
    } else if (image_path.empty()) {
      image_path = argv[i];
    } else if (ref_path.empty()) {
      ref_path = argv[i];
    } else {
      return usage();
    }
  }
  if (ref_path.empty()) return usage();

  whisker::Image x, r;
  try {
    x = whisker::read_pfm(image_path);
    r = whisker::read_pfm(ref_path);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "whisker-compare: %s\n", e.what());
    return 2;
  }
  if (x.width != r.width || x.height != r.height) {
    std::fprintf(stderr, "whisker-compare: %s is %dx%d but %s is %dx%d\n", image_path.c_str(),
                 x.width, x.height, ref_path.c_str(), r.width, r.height);
    return 2;
  }

  const Metrics m = compare(x, r, white);
  std::printf("mse %.6g rmse %.6g rel_mse %.6g mean %.6g ref_mean %.6g mean_diff %.6g z %.3g",
              m.mse, m.rmse, m.rel_mse, m.mean_image, m.mean_reference, m.mean_diff,
              m.mean_diff_z);
  if (m.nonfinite) std::printf(" nonfinite %lld", m.nonfinite);
  nlohmann::json by_scale = nlohmann::json::object();
  for (int k : scales) {
    const double e = mse_at_scale(x, r, white, k);
    by_scale[std::to_string(k)] = e;
    std::printf(" mse@%d %.6g", k, e);
  }
  std::printf("\n");

  if (!json_path.empty()) {
    const nlohmann::json j = {{"image", image_path},       {"reference", ref_path},
                              {"width", m.width},          {"height", m.height},
                              {"white", white},
                              {"mse", m.mse},              {"rmse", m.rmse},
                              {"rel_mse", m.rel_mse},      {"mean_image", m.mean_image},
                              {"mean_reference", m.mean_reference},
                              {"mean_diff", m.mean_diff},  {"mean_diff_z", m.mean_diff_z},
                              {"nonfinite", m.nonfinite},
                              {"mse_by_scale", by_scale}};
    std::ofstream out(json_path);
    out << j.dump(2) << "\n";
    if (!out) {
      std::fprintf(stderr, "whisker-compare: %s: cannot write\n", json_path.c_str());
      return 2;
    }
  }
  return 0;
}
