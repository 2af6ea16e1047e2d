#include "viewer/display.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include <glad/gl.h>

namespace whisker {

namespace fs = std::filesystem;

std::string find_shader_dir() {
  std::vector<fs::path> candidates;
  if (const char* env = std::getenv("WHISKER_SHADERS")) candidates.emplace_back(env);
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {  // a build tree (a link to the source's shaders/), or installed
    candidates.push_back(exe.parent_path() / "shaders");
    candidates.push_back(exe.parent_path() / "../share/whisker/shaders");
  }
  for (const fs::path& dir : candidates)
    if (fs::exists(dir / "display.frag", ec)) return dir.string();
  return {};
}

static bool read_text(const fs::path& path, std::string& out) {
  std::ifstream in(path);
  if (!in) return false;
  std::ostringstream ss;
  ss << in.rdbuf();
  out = ss.str();
  return true;
}

// Whether a shader compiled or a program linked (`status`); if not, `error`
// is `prefix` and GL's log.
template <class GetIv, class GetLog>
static bool gl_ok(GLuint object, GetIv get_iv, GLenum status, GetLog get_log,
                  const std::string& prefix, std::string& error) {
  GLint ok = 0;
  get_iv(object, status, &ok);
  if (ok) return true;
  char log[2048] = {};
  get_log(object, sizeof log, nullptr, log);
  error = prefix + log;
  return false;
}

static GLuint compile(GLenum type, const std::string& src, const std::string& name,
                      std::string& error) {
  GLuint sh = glCreateShader(type);
  const char* text = src.c_str();
  glShaderSource(sh, 1, &text, nullptr);
  glCompileShader(sh);
  if (!gl_ok(sh, glGetShaderiv, GL_COMPILE_STATUS, glGetShaderInfoLog, name + ": ", error)) {
    glDeleteShader(sh);
    return 0;
  }
  return sh;
}

bool Display::init(std::string& error) {
  const std::string dir = find_shader_dir();
  if (dir.empty()) {
    error = "display shaders not found (set WHISKER_SHADERS to the shaders/ folder)";
    return false;
  }
  std::string vs_src, fs_src;
  const fs::path vs_path = fs::path(dir) / "display.vert";
  const fs::path fs_path = fs::path(dir) / "display.frag";
  if (!read_text(vs_path, vs_src) || !read_text(fs_path, fs_src)) {
    error = "cannot read " + vs_path.string() + " or " + fs_path.string();
    return false;
  }
  GLuint vs = compile(GL_VERTEX_SHADER, vs_src, vs_path.string(), error);
  if (!vs) return false;
  GLuint fsh = compile(GL_FRAGMENT_SHADER, fs_src, fs_path.string(), error);
  if (!fsh) {
    glDeleteShader(vs);
    return false;
  }
  program_ = glCreateProgram();
  glAttachShader(program_, vs);
  glAttachShader(program_, fsh);
  glLinkProgram(program_);
  glDeleteShader(vs);
  glDeleteShader(fsh);
  if (!gl_ok(program_, glGetProgramiv, GL_LINK_STATUS, glGetProgramInfoLog, "display shaders: ",
             error))
    return false;
  loc_spp_ = glGetUniformLocation(program_, "spp");
  loc_exposure_ = glGetUniformLocation(program_, "exposure");
  loc_gamma_ = glGetUniformLocation(program_, "gamma");
  loc_mode_ = glGetUniformLocation(program_, "mode");
  loc_lum_ = glGetUniformLocation(program_, "lum_weights");
  loc_sums_ = glGetUniformLocation(program_, "sums");
  loc_sq_ = glGetUniformLocation(program_, "sums_sq");
  loc_tonemap_ = glGetUniformLocation(program_, "tonemap");

  glGenVertexArrays(1, &vao_);  // core profile: a bound VAO even with no attributes
  for (GLuint* t : {&tex_, &tex_sq_}) {
    glGenTextures(1, t);
    glBindTexture(GL_TEXTURE_2D, *t);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
  return true;
}

Display::~Display() {
  if (tex_) glDeleteTextures(1, &tex_);
  if (tex_sq_) glDeleteTextures(1, &tex_sq_);
  if (vao_) glDeleteVertexArrays(1, &vao_);
  if (cache_) glDeleteTextures(1, &cache_);
  if (fbo_) glDeleteFramebuffers(1, &fbo_);
  if (program_) glDeleteProgram(program_);
}

void Display::upload(const Snapshot& s, bool with_sq) {
  if (s.width <= 0 || s.height <= 0 || s.sum.size() < std::size_t(s.width) * s.height * 3)
    return;
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  const bool resize = s.width != width_ || s.height != height_;
  // The textures are float (GL takes no double texels): the snapshot's
  // double sums are rounded as mean_image rounds them for the files. GL has
  // copied the staging buffer when each call returns, so it is reused.
  staging_.assign(s.sum.begin(), s.sum.end());
  glBindTexture(GL_TEXTURE_2D, tex_);
  if (resize)
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, s.width, s.height, 0, GL_RGB, GL_FLOAT,
                 staging_.data());
  else
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, s.width, s.height, GL_RGB, GL_FLOAT,
                    staging_.data());
  if (with_sq && s.sum_sq.size() >= std::size_t(s.width) * s.height) {
    staging_.assign(s.sum_sq.begin(), s.sum_sq.end());
    glBindTexture(GL_TEXTURE_2D, tex_sq_);
    if (resize || !sq_valid_)
      glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, s.width, s.height, 0, GL_RED, GL_FLOAT,
                   staging_.data());
    else
      glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, s.width, s.height, GL_RED, GL_FLOAT,
                      staging_.data());
    sq_valid_ = true;
  } else if (resize) {
    sq_valid_ = false;
  }
  width_ = s.width;
  height_ = s.height;
  stride_ = std::max(1, s.stride);
  cache_valid_ = false;
}

void Display::draw(const PixelRect& area, int framebuffer_height, float spp,
                   const DisplayParams& p) {
  draw_columns(area, framebuffer_height, spp, p, 0.0f, 1.0f);
}

void Display::draw_columns(const PixelRect& area, int framebuffer_height, float spp,
                           const DisplayParams& p, float from, float to) {
  if (!width_ || !height_ || area.w <= 0 || area.h <= 0) return;
  if (!cache_valid_ || spp != cache_spp_ || p.exposure != cache_params_.exposure ||
      p.gamma != cache_params_.gamma || p.mode != cache_params_.mode ||
      p.tonemap != cache_params_.tonemap)
    map_to_cache(spp, p);
  // Whole image pixels on both sides, so a wipe never stretches a column.
  const int c0 = int(std::lround(std::clamp(from, 0.0f, 1.0f) * cache_w_));
  const int c1 = int(std::lround(std::clamp(to, 0.0f, 1.0f) * cache_w_));
  if (c1 <= c0) return;
  const int x0 = area.x + int(std::lround(double(c0) * area.w / cache_w_));
  const int x1 = area.x + int(std::lround(double(c1) * area.w / cache_w_));
  // Magnified or 1:1 pixels stay crisp; a reduced image is filtered, and so
  // is a coarse quick pass's (its texels are not the image's pixels: drawn
  // as blocks they would be a mosaic).
  const int y0 = framebuffer_height - area.y - area.h;
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glDisable(GL_SCISSOR_TEST);
  glBlitFramebuffer(c0, 0, c1, cache_h_, x0, y0, x1, y0 + area.h,
                    GL_COLOR_BUFFER_BIT,
                    area.w < cache_w_ || stride_ > 1 ? GL_LINEAR : GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void Display::map_to_cache(float spp, const DisplayParams& p) {
  if (!fbo_) glGenFramebuffers(1, &fbo_);
  if (!cache_) glGenTextures(1, &cache_);
  if (cache_w_ != width_ || cache_h_ != height_) {
    glBindTexture(GL_TEXTURE_2D, cache_);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width_, height_, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 nullptr);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, cache_, 0);
    cache_w_ = width_;
    cache_h_ = height_;
  }
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, cache_w_, cache_h_);
  glDisable(GL_BLEND);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glUseProgram(program_);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, tex_sq_);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, tex_);
  glUniform1i(loc_sums_, 0);
  glUniform1i(loc_sq_, 1);
  glUniform1f(loc_spp_, spp);
  glUniform1f(loc_exposure_, p.exposure);
  glUniform1f(loc_gamma_, p.gamma);
  glUniform1i(loc_mode_, p.mode);
  glUniform1i(loc_tonemap_, p.tonemap);
  glUniform3f(loc_lum_, float(kLuminanceWeights[0]), float(kLuminanceWeights[1]),
              float(kLuminanceWeights[2]));
  glBindVertexArray(vao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glUseProgram(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  cache_valid_ = true;
  cache_spp_ = spp;
  cache_params_ = p;
}

PixelRect fit_image(const PixelRect& area, int image_w, int image_h) {
  if (image_w <= 0 || image_h <= 0 || area.w <= 0 || area.h <= 0) return {};
  const double sx = double(area.w) / image_w, sy = double(area.h) / image_h;
  double s = std::min(sx, sy);
  if (s >= 1.0) s = std::floor(s);
  const int w = std::max(1, int(image_w * s)), h = std::max(1, int(image_h * s));
  return {area.x + (area.w - w) / 2, area.y + (area.h - h) / 2, w, h};
}

std::vector<unsigned char> read_framebuffer(int width, int height) {
  std::vector<unsigned char> rows(std::size_t(width) * height * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, rows.data());
  // GL's row 0 is the bottom.
  std::vector<unsigned char> out(rows.size());
  const std::size_t stride = std::size_t(width) * 3;
  for (int y = 0; y < height; ++y)
    std::copy_n(rows.data() + std::size_t(height - 1 - y) * stride, stride,
                out.data() + std::size_t(y) * stride);
  return out;
}

}  // namespace whisker
