#include "viewer/readout.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "viewer/debug_views.h"

namespace whisker {

ProgressInfo estimate_progress(const ProgressInput& in) {
  ProgressInfo p;
  if (in.pass_spp > 0 && in.tiles_total > 0)
    p.pass_fraction = std::clamp(double(in.tiles_done) / in.tiles_total, 0.0, 1.0);
  p.done_spp = double(in.spp_done) + p.pass_fraction * in.pass_spp;
  p.elapsed = in.seconds_done + (in.pass_spp > 0 ? in.pass_seconds : 0.0);
  // The rate of the passes published so far: a pass in flight, or the
  // quick passes after an edit, say nothing about it yet.
  if (in.spp_done > 0 && in.seconds_done > 0.0)
    p.spp_per_second = double(in.spp_done) / in.seconds_done;
  if (in.target_spp > 0) {
    p.fraction = std::clamp(p.done_spp / in.target_spp, 0.0, 1.0);
    if (p.done_spp >= in.target_spp)
      p.eta = 0.0;
    else if (p.spp_per_second > 0.0)
      p.eta = (in.target_spp - p.done_spp) / p.spp_per_second;
  }
  return p;
}

std::string format_duration(double seconds) {
  char buf[48];
  if (!(seconds >= 0.0) || !std::isfinite(seconds)) return "-";
  if (seconds < 60.0) {
    std::snprintf(buf, sizeof buf, "%.1f s", seconds);
  } else if (seconds < 3600.0) {
    const long s = std::lround(seconds);
    std::snprintf(buf, sizeof buf, "%ldm %02lds", s / 60, s % 60);
  } else {
    const long m = std::lround(seconds / 60.0);
    std::snprintf(buf, sizeof buf, "%ldh %02ldm", m / 60, m % 60);
  }
  return buf;
}

PixelReadout read_pixel(const Snapshot& s, int x, int y) {
  PixelReadout r;
  if (x < 0 || y < 0 || x >= s.width || y >= s.height || s.spp == 0) return r;
  const std::size_t p = std::size_t(y) * s.width + x;
  if (s.sum.size() < 3 * (p + 1)) return r;
  const double n = double(s.spp);
  for (int c = 0; c < 3; ++c) r.rgb[c] = float(s.sum[3 * p + c] / n);
  r.luminance = luminance(glm::vec3(r.rgb[0], r.rgb[1], r.rgb[2]));
  r.samples = s.spp;
  if (s.spp >= 2 && !s.quick && s.sum_sq.size() > p) {
    // Population variance / (n - 1) = sample variance / n: the mean's variance.
    const double var = std::max(0.0, s.sum_sq[p] / n - r.luminance * r.luminance);
    r.std_error = std::sqrt(var / (n - 1.0));
  }
  return r;
}

std::vector<std::string> readout_lines(const PixelReadout& r, int x, int y, bool held) {
  char buf[128];
  std::vector<std::string> lines;
  std::snprintf(buf, sizeof buf, "pixel (%d, %d)%s", x, y, held ? "  [held image]" : "");
  lines.push_back(buf);
  std::snprintf(buf, sizeof buf, "radiance  %.4g  %.4g  %.4g", r.rgb[0], r.rgb[1], r.rgb[2]);
  lines.push_back(buf);
  if (r.std_error >= 0.0 && r.luminance > 0.0)
    std::snprintf(buf, sizeof buf, "luminance %.4g +- %.3g (%.3g %%)", r.luminance, r.std_error,
                  100.0 * r.std_error / r.luminance);
  else if (r.std_error >= 0.0)
    std::snprintf(buf, sizeof buf, "luminance %.4g +- %.3g", r.luminance, r.std_error);
  else
    std::snprintf(buf, sizeof buf, "luminance %.4g  (error needs 2 samples)", r.luminance);
  lines.push_back(buf);
  std::snprintf(buf, sizeof buf, "%llu sample%s (std. error of the pixel mean)",
                (unsigned long long)r.samples, r.samples == 1 ? "" : "s");
  lines.push_back(buf);
  return lines;
}

std::string stop_reason(double rse, double seconds, float noise_pct, float max_seconds) {
  char text[64];
  if (noise_pct > 0.0f && std::isfinite(rse) && 100.0 * rse <= noise_pct) {
    std::snprintf(text, sizeof text, "noise %.3g %% reached", double(noise_pct));
    return text;
  }
  if (max_seconds > 0.0f && seconds >= max_seconds) return format_duration(max_seconds) + " reached";
  return {};
}

BoxPlace place_readout(float mx, float my, float w, float h, float ax, float ay, float aw, float ah) {
  // Away from the image's centre on each axis, beside the pointer; the other
  // side where that leaves the image.
  const float right_x = mx + 16.0f, left_x = mx - 8.0f - w;
  const float below_y = my + 8.0f, above_y = my - 8.0f - h;
  const bool go_right = mx >= ax + 0.5f * aw, go_down = my >= ay + 0.5f * ah;
  BoxPlace p{go_right ? right_x : left_x, go_down ? below_y : above_y};
  if (p.x + w > ax + aw) p.x = std::max(ax, left_x);
  if (p.x < ax) p.x = std::min(right_x, std::max(ax, ax + aw - w));
  if (p.y + h > ay + ah) p.y = std::max(ay, above_y);
  if (p.y < ay) p.y = std::min(below_y, std::max(ay, ay + ah - h));
  return p;
}

float aces_narkowicz(float x) {
  x = std::max(x, 0.0f);
  const float a = 2.51f, b = 0.03f, c = 2.43f, d = 0.59f, e = 0.14f;
  return std::clamp(x * (a * x + b) / (x * (c * x + d) + e), 0.0f, 1.0f);
}

void heat_colour(float t, float out[3]) {
  t = std::clamp(t, 0.0f, 1.0f);
  for (int c = 0; c < 3; ++c)
    out[c] = std::clamp(1.5f - std::fabs(4.0f * t - float(3 - c)), 0.0f, 1.0f);
}

namespace {

unsigned char to8(float v) { return static_cast<unsigned char>(std::floor(v * 255.0f)); }

}  // namespace

std::vector<unsigned char> map_like_display(const Snapshot& s, const DisplayParams& p) {
  const std::size_t pixels = std::size_t(std::max(0, s.width)) * std::max(0, s.height);
  std::vector<unsigned char> out(pixels * 3, 0);
  if (s.sum.size() < pixels * 3) return out;
  const float spp = float(s.spp);
  const float inv = s.spp ? 1.0f / spp : 0.0f;  // as mean_image()
  // exposure * 255^gamma: 1 for the report's mapping (exposure 1/255^2.2).
  float report_k = float(double(p.exposure) * std::pow(255.0, double(p.gamma)));
  if (std::fabs(report_k - 1.0f) < 1e-5f) report_k = 1.0f;
  for (std::size_t k = 0; k < pixels; ++k) {
    float mean[3];
    for (int c = 0; c < 3; ++c) mean[c] = float(s.sum[3 * k + c]) * inv;
    float v[3];
    if (p.mode == kViewNoise) {
      const float m = luminance(glm::vec3(mean[0], mean[1], mean[2]));
      const float sq = s.sum_sq.size() > k ? s.sum_sq[k] : 0.0f;
      const float var = std::max(sq / std::max(spp, 1.0f) - m * m, 0.0f);
      const float rel = std::sqrt(var / std::max(spp - 1.0f, 1.0f)) / m;
      if (m > 0.0f)
        heat_colour((std::log(rel) / std::log(10.0f) + 3.0f) / 3.0f, v);
      else
        v[0] = v[1] = v[2] = 0.0f;
    } else if (p.tonemap == kTonemapAces) {
      for (int c = 0; c < 3; ++c)
        v[c] = std::min(std::pow(aces_narkowicz(mean[c] * p.exposure), 1.0f / p.gamma), 1.0f);
    } else {
      // The report's mapping in its own form, min(255, (k L)^(1/gamma)) with
      // k = 1 at exposure 0: at the defaults the PNG matches the headless one
      // to the bit.
      for (int c = 0; c < 3; ++c) {
        const float x = std::max(mean[c] * report_k, 0.0f);
        const float w = x > 0.0f ? std::pow(x, 1.0f / p.gamma) : 0.0f;
        out[3 * k + c] = w >= 255.0f ? 255 : static_cast<unsigned char>(w);
      }
      continue;
    }
    for (int c = 0; c < 3; ++c) out[3 * k + c] = to8(v[c]);
  }
  return out;
}

std::string free_stem(const std::string& dir, const std::string& stem,
                      const std::vector<std::string>& extensions) {
  namespace fs = std::filesystem;
  for (int k = 1;; ++k) {
    const std::string name = k == 1 ? stem : stem + "-" + std::to_string(k);
    bool taken = false;
    std::error_code ec;
    for (const std::string& ext : extensions) taken |= fs::exists(fs::path(dir) / (name + ext), ec);
    if (!taken) return name;
  }
}

}  // namespace whisker
