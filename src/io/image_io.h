// Writing images: PNG (the report's mapping), PFM and EXR (linear radiance).
// Every writer goes through a temporary file renamed into place after
// checked writes (io/atomic_file.h), so an interrupted run or a full
// disk never leaves a broken image under its final name.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "io/image_error.h"
#include "render/image.h"

namespace whisker {

// The report's display mapping: min(255, L^(1/2.2)) with L the radiance
// (light intensity applied), docs/SCENES.md "Pixel value shown".
unsigned char to_srgb8(float radiance);

// The report's mapping of `img` (to_srgb8) as an 8-bit PNG.
void write_png(const std::string& path, const Image& img);
// 8-bit RGB pixels, row 0 at the top, as they are (a window's screenshot).
void write_png_rgb8(const std::string& path, int width, int height,
                    const std::vector<unsigned char>& rgb);
// Name and text of a string attribute in an EXR header (what was rendered how).
using ImageAttributes = std::vector<std::pair<std::string, std::string>>;

// A channel beside R, G, B in an EXR: its name and one float a pixel (row
// 0 at the top).
struct ImageLayer {
  std::string name;
  std::vector<float> values;
};
using ImageLayers = std::vector<ImageLayer>;

void write_pfm(const std::string& path, const Image& img);
// Throws if built without OpenEXR; `attributes` go into the header as
// strings, `layers` as FLOAT channels (each of the image's size).
void write_exr(const std::string& path, const Image& img, const ImageAttributes& attributes = {},
               const ImageLayers& layers = {});
// By extension, any case: .pfm or .exr (a PFM has no room for attributes or
// layers).
void write_float_image(const std::string& path, const Image& img,
                       const ImageAttributes& attributes = {}, const ImageLayers& layers = {});

// The radiance that the report's mapping min(255, L^(1/2.2)) shows as full
// white: 255^2.2 (docs/SCENES.md "Pixel value shown").
float report_white();
// `img` in display-referred units, 1.0 = report_white(): an HDR viewer at
// exposure 0 (sRGB, about L^(1/2.2)) then shows what the PNG shows, unclipped.
Image display_referred(const Image& img);
Image read_pfm(const std::string& path);
bool have_exr();

}  // namespace whisker
