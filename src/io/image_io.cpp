#include "io/image_io.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <stb/stb_image_write.h>

#ifdef WHISKER_HAVE_OPENEXR
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#endif

#include "io/atomic_file.h"
#include "scene/file_name.h"

namespace whisker {

namespace fs = std::filesystem;

unsigned char to_srgb8(float radiance) {
  // docs/SCENES.md: min(255, L^(1/2.2)); negative or NaN never happen in the
  // buffer, but clamp them to black rather than trust that.
  if (!(radiance > 0.0f)) return 0;
  const float v = std::pow(radiance, 1.0f / 2.2f);
  return v >= 255.0f ? 255 : static_cast<unsigned char>(v);
}

namespace {

void check(const Image& img, const std::string& path) {
  if (img.width <= 0 || img.height <= 0 ||
      img.rgb.size() != std::size_t(img.width) * img.height * 3)
    throw ImageError(path + ": empty or malformed image");
}

}  // namespace

void write_png(const std::string& path, const Image& img) {
  check(img, path);
  std::vector<unsigned char> px(img.rgb.size());
  std::transform(img.rgb.begin(), img.rgb.end(), px.begin(), to_srgb8);
  write_png_rgb8(path, img.width, img.height, px);
}

void write_png_rgb8(const std::string& path, int width, int height,
                    const std::vector<unsigned char>& rgb) {
  if (width <= 0 || height <= 0 || rgb.size() != std::size_t(width) * height * 3)
    throw ImageError(path + ": empty or malformed image");
  // Encoded in memory, then written with checked calls: stb's own file
  // writer ignores fwrite/fclose errors (a full disk gave a truncated PNG).
  std::string bytes;
  const auto append = [](void* to, void* data, int size) {
    static_cast<std::string*>(to)->append(static_cast<const char*>(data), std::size_t(size));
  };
  if (!stbi_write_png_to_func(append, &bytes, width, height, 3, rgb.data(), width * 3))
    throw ImageError(path + ": cannot encode the PNG");
  write_bytes_atomically(path, bytes);
}

void write_pfm(const std::string& path, const Image& img) {
  check(img, path);
  // PFM: "PF", size, negative scale = little endian; rows bottom to top.
  std::string bytes = "PF\n" + std::to_string(img.width) + " " + std::to_string(img.height) +
                      "\n-1.0\n";
  const std::size_t row = sizeof(float) * std::size_t(img.width) * 3;
  bytes.reserve(bytes.size() + row * std::size_t(img.height));
  for (int y = img.height - 1; y >= 0; --y)
    bytes.append(reinterpret_cast<const char*>(&img.rgb[std::size_t(y) * img.width * 3]), row);
  write_bytes_atomically(path, bytes);
}

Image read_pfm(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ImageError(path + ": cannot open");
  std::string magic;
  Image img;
  float scale = 0.0f;
  in >> magic >> img.width >> img.height >> scale;
  in.get();
  if (magic != "PF" || img.width <= 0 || img.height <= 0 || scale >= 0.0f)
    throw ImageError(path + ": not a little-endian RGB PFM file");
  img.rgb.resize(std::size_t(img.width) * img.height * 3);
  for (int y = img.height - 1; y >= 0; --y)
    in.read(reinterpret_cast<char*>(&img.rgb[std::size_t(y) * img.width * 3]),
            std::streamsize(sizeof(float)) * img.width * 3);
  if (!in) throw ImageError(path + ": truncated PFM file");
  return img;
}

bool have_exr() {
#ifdef WHISKER_HAVE_OPENEXR
  return true;
#else
  return false;
#endif
}

void write_exr(const std::string& path, const Image& img, const ImageAttributes& attributes,
               const ImageLayers& layers) {
  check(img, path);
  for (const ImageLayer& l : layers)
    if (l.values.size() != std::size_t(img.width) * img.height)
      throw ImageError(path + ": layer " + l.name + " is not of the image's size");
#ifdef WHISKER_HAVE_OPENEXR
  write_file_atomically(path, [&](const std::string& tmp) {
    try {
      Imf::Header header(img.width, img.height);
      for (const char* c : {"R", "G", "B"}) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
      for (const ImageLayer& l : layers) header.channels().insert(l.name, Imf::Channel(Imf::FLOAT));
      for (const auto& [name, text] : attributes)
        header.insert(name, Imf::StringAttribute(text));
      Imf::OutputFile file(tmp.c_str(), header);
      Imf::FrameBuffer fb;
      char* base = reinterpret_cast<char*>(const_cast<float*>(img.rgb.data()));
      const std::size_t xs = 3 * sizeof(float), ys = xs * img.width;
      fb.insert("R", Imf::Slice(Imf::FLOAT, base, xs, ys));
      fb.insert("G", Imf::Slice(Imf::FLOAT, base + sizeof(float), xs, ys));
      fb.insert("B", Imf::Slice(Imf::FLOAT, base + 2 * sizeof(float), xs, ys));
      for (const ImageLayer& l : layers)
        fb.insert(l.name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(l.values.data())),
                                     sizeof(float), sizeof(float) * img.width));
      file.setFrameBuffer(fb);
      file.writePixels(img.height);
      return true;
    } catch (const std::exception& e) {
      return false;
    }
  });
#else
  throw ImageError(path + ": this build has no OpenEXR support; write a .pfm instead");
#endif
}

void write_float_image(const std::string& path, const Image& img,
                       const ImageAttributes& attributes, const ImageLayers& layers) {
  const std::string ext = lower_extension(path);  // x.EXR too
  if (ext == ".pfm") return write_pfm(path, img);
  if (ext == ".exr") return write_exr(path, img, attributes, layers);
  throw ImageError(path + ": unknown float image type \"" + ext + "\" (use .pfm or .exr)");
}

float report_white() { return std::pow(255.0f, 2.2f); }

Image display_referred(const Image& img) {
  Image out = img;
  const float scale = 1.0f / report_white();
  for (float& v : out.rgb) v *= scale;
  return out;
}

}  // namespace whisker
