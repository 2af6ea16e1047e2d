// The GL side of the window: the accumulation as a float texture, drawn by
// shaders/display.{vert,frag}. Needs a current OpenGL 3.3 context.
#pragma once

#include <string>
#include <vector>

#include "render/progressive.h"

namespace whisker {

struct DisplayParams {
  float exposure = 1.0f;  // linear scale
  float gamma = 2.2f;
  int mode = 0;           // a ViewMode (viewer/debug_views.h): kViewImage, kViewNoise, ...
  int tonemap = 0;        // 0 the report's mapping (clip), 1 ACES filmic
};

// A rectangle in framebuffer pixels, origin at the top left.
struct PixelRect {
  int x = 0, y = 0, w = 0, h = 0;
};

class Display {
 public:
  // Compiles the shaders; false (with `error` set) if they cannot be found
  // or do not compile.
  bool init(std::string& error);
  ~Display();

  // Uploads the snapshot's sums (and sums of squares if `with_sq`); call only
  // when the snapshot changed.
  void upload(const Snapshot& s, bool with_sq);
  // Draws the image into `area` of the default framebuffer. The mapped image
  // is cached in an 8-bit texture and re-mapped only when the sums or the
  // display parameters change: a plain copy is all most frames pay.
  void draw(const PixelRect& area, int framebuffer_height, float spp,
            const DisplayParams& p);
  // Draws only the columns from `from` to `to` (fractions of the width) of
  // the image at the same place: the held image's side of a wipe.
  void draw_columns(const PixelRect& area, int framebuffer_height, float spp,
                    const DisplayParams& p, float from, float to);

  // The image's size in its own pixels: a coarse quick pass's texels
  // (Snapshot::stride) are stride x stride of them.
  int width() const { return width_ * stride_; }
  int height() const { return height_ * stride_; }

 private:
  void map_to_cache(float spp, const DisplayParams& p);

  unsigned program_ = 0, vao_ = 0, tex_ = 0, tex_sq_ = 0;
  unsigned fbo_ = 0, cache_ = 0;  // the mapped image, RGBA8, image size
  int width_ = 0, height_ = 0;  // of the texture
  int stride_ = 1;              // image pixels per texel, each way
  int cache_w_ = 0, cache_h_ = 0;
  bool sq_valid_ = false;
  // The sums rounded to float on their way to a texture, kept between
  // uploads so a pass does not allocate an image's worth each time.
  std::vector<float> staging_;
  bool cache_valid_ = false;
  float cache_spp_ = -1.0f;
  DisplayParams cache_params_;
  int loc_spp_ = -1, loc_exposure_ = -1, loc_gamma_ = -1, loc_mode_ = -1,
      loc_lum_ = -1, loc_sums_ = -1, loc_sq_ = -1, loc_tonemap_ = -1;
};

// Where the image goes inside `area`: 1:1 or an integer zoom if it fits
// (pixel-exact, so a screenshot compares with the headless PNG), else scaled
// down keeping its aspect; centred.
PixelRect fit_image(const PixelRect& area, int image_w, int image_h);

// Reads the back buffer (RGB, row 0 at the top).
std::vector<unsigned char> read_framebuffer(int width, int height);

// The folder holding display.vert/.frag: $WHISKER_SHADERS, next to the
// executable, or the source tree's shaders/.
std::string find_shader_dir();

}  // namespace whisker
