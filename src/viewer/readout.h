// The viewer's numbers that need no window: progress and time left, one
// pixel's statistics, the display mapping on the CPU (for saving what the
// window shows) and a file name that overwrites nothing.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "render/film.h"
#include "render/progressive.h"
#include "viewer/display.h"

namespace whisker {

// Progress of a generation toward its target. Samples are per pixel: one
// sample is one camera ray through each pixel; with splitting it continues
// as several paths (up to 16 with 4 x 4), so samples/s is not paths/s.
struct ProgressInfo {
  double done_spp = 0.0;       // samples per pixel, counting the pass in flight
  double fraction = -1.0;      // toward the target, 0..1; < 0: no target
  double pass_fraction = 0.0;  // of the pass in flight
  double elapsed = 0.0;        // render seconds, the pass in flight included
  double spp_per_second = 0.0; // measured; 0 until something finished
  double eta = -1.0;           // seconds to the target; < 0: unknown / none
};

struct ProgressInput {
  std::uint64_t spp_done = 0;  // in the last published pass
  int target_spp = 0;          // 0: never stop
  double seconds_done = 0.0;   // render time of the published passes
  int pass_spp = 0;            // the pass in flight (0: none)
  int tiles_done = 0, tiles_total = 0;
  double pass_seconds = 0.0;
};

ProgressInfo estimate_progress(const ProgressInput& in);

// "1h 02m", "3m 05s", "12.3 s" (as the headless progress line).
std::string format_duration(double seconds);

// Why a render stops before its target (Sampling > stop at): "noise 2 %
// reached" once the relative standard error `rse` is at most noise_pct
// percent, "10.0 s reached" once its render time is max_seconds; "" while
// neither is (a limit of 0 is off; an unknown error, NaN, is not low).
std::string stop_reason(double rse, double seconds, float noise_pct, float max_seconds);

// Pixel (x, y) of a snapshot: mean radiance and the standard error of its
// luminance mean (from the per-pixel sums of squares).
struct PixelReadout {
  float rgb[3] = {0, 0, 0};
  double luminance = 0.0;
  double std_error = -1.0;  // < 0: needs 2 samples
  std::uint64_t samples = 0;
};
PixelReadout read_pixel(const Snapshot& s, int x, int y);

// The readout's lines as the tooltip over the image shows them: the pixel
// (and "[held image]" on the held side of a comparison), its radiance, its
// luminance with the standard error, and "1 sample" / "N samples".
std::vector<std::string> readout_lines(const PixelReadout& r, int x, int y, bool held);

// Where a box of w x h (the readout) goes for the mouse at (mx, my), all in
// window units: beside the pointer on the side away from the centre of the
// image area (ax, ay, aw, ah), on each axis (right of the pointer in the
// right half, above it in the top half, ...), so it leaves the middle of the
// image (the subject) in view; on the other side where it would leave the
// area, so it never covers the panel beside the image.
struct BoxPlace {
  float x = 0, y = 0;
};
BoxPlace place_readout(float mx, float my, float w, float h, float ax, float ay, float aw, float ah);

// Tone curves of the display (DisplayParams::tonemap).
enum Tonemap : int { kTonemapReport = 0, kTonemapAces = 1 };
// Narkowicz 2015, "ACES Filmic Tone Mapping Curve": a rational fit of the
// ACES reference rendering transform; input linear, output in [0, 1].
float aces_narkowicz(float x);

// The noise view's false colour (heat() in shaders/display.frag): blue,
// cyan, green, yellow, red for t from 0 to 1.
void heat_colour(float t, float out[3]);

// The 8-bit RGB image (row 0 at the top) that shaders/display.frag draws for
// `p`: the same exposure, tone curve, gamma and view, so a saved PNG is what
// the window shows.
std::vector<unsigned char> map_like_display(const Snapshot& s, const DisplayParams& p);

// `dir/stem` + the first of "", "-2", "-3", ... for which no file with any of
// `extensions` exists. Returns the stem chosen (without the folder).
std::string free_stem(const std::string& dir, const std::string& stem,
                      const std::vector<std::string>& extensions);

}  // namespace whisker
