// OBJ loading: a validating line scan that names the file and line of bad
// input, then tinyobjloader for the parse and polygon triangulation.
#include <algorithm>
#include <charconv>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string_view>

#include <glm/common.hpp>
#include <tiny_obj_loader.h>

#include "scene/mesh_io.h"
#include "scene/quote.h"

namespace whisker {
namespace {

[[noreturn]] void fail(const std::string& path, std::size_t line, const std::string& what) {
  std::ostringstream m;
  m << path;
  if (line > 0) m << ":" << line;
  m << ": " << what;
  throw MeshError(m.str());
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::string_view next_token(std::string_view& s) {
  s = trim(s);
  std::size_t n = 0;
  while (n < s.size() && s[n] != ' ' && s[n] != '\t') ++n;
  const std::string_view tok = s.substr(0, n);
  s.remove_prefix(n);
  return tok;
}

// Keywords of the OBJ format (and its free-form geometry statements, which we
// accept and ignore as tinyobjloader does).
bool known_keyword(std::string_view k) {
  static constexpr std::string_view kKeys[] = {
      "v", "vn", "vt", "vp", "f", "l", "p", "g", "o", "s", "usemtl", "mtllib", "cstype",
      "deg", "bmat", "step", "curv", "curv2", "surf", "parm", "trim", "hole", "scrv", "sp",
      "end", "con", "mg", "bevel", "c_interp", "d_interp", "lod", "shadow_obj", "trace_obj",
      "ctech", "stech", "t"};
  for (std::string_view key : kKeys)
    if (k == key) return true;
  return false;
}

// The largest OBJ file read. Loading takes up to about 12 bytes of memory a
// byte of file (the text, tinyobjloader's copy and arrays, the vertices in
// double and float): about 3 GB at this cap.
constexpr std::uintmax_t kMaxObjBytes = std::uintmax_t(256) << 20;

// The longest line (a face of kMaxFaceCorners corners takes under 30 KB).
constexpr std::size_t kMaxObjLine = std::size_t(1) << 20;

// The most corners a face may have (a 1,000-gon triangulates in about 3 ms).
constexpr int kMaxFaceCorners = 1000;

struct Scan {
  std::size_t line_no = 0;       // lines scanned so far
  std::size_t vertices = 0, faces = 0;
  long max_index = 0;            // largest positive vertex index seen
  std::size_t max_index_line = 0;
  std::vector<std::string> mtllibs;
  std::vector<double> coords;  // the vertices' coordinates, read in double
};

// The three numbers of a "v" or "vn" line, each finite in float (what the
// renderer keeps), appended to `out` if given.
void three_numbers(std::string_view& rest, const std::string& path, std::size_t line_no,
                   const std::string& what, std::vector<double>* out) {
  for (int i = 0; i < 3; ++i) {
    const std::string tok(next_token(rest));
    char* e = nullptr;
    const double x = tok.empty() ? 0.0 : std::strtod(tok.c_str(), &e);
    if (tok.empty() || e != tok.c_str() + tok.size()) fail(path, line_no, what + " needs three numbers");
    if (!std::isfinite(float(x))) fail(path, line_no, what + " coordinate is NaN or infinite");
    if (out) out->push_back(x);
  }
}

// Checks every line of `text` (whole lines, the last one's '\n' optional):
// known keyword, finite numeric vertex coordinates, face indices in range
// (negative ones relative to the vertices read so far). Called on each piece
// of the file as it is read, so that the first bad line ends the read.
void scan_lines(Scan& s, const std::string& path, std::string_view text) {
  std::size_t& line_no = s.line_no;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    std::string_view line(text.data() + pos, end - pos);
    pos = end + 1;
    ++line_no;
    for (char ch : line) {
      const unsigned char c = static_cast<unsigned char>(ch);
      if (c == 0 || (c < 0x20 && c != '\t' && c != '\r') || c == 0x7f)
        fail(path, line_no, "binary data, not a text OBJ file");
    }
    std::string_view rest = line;
    const std::size_t hash = rest.find('#');
    if (hash != std::string_view::npos) rest = rest.substr(0, hash);
    const std::string_view key = next_token(rest);
    if (key.empty()) continue;
    if (!known_keyword(key))
      fail(path, line_no, "unrecognised line '" + std::string(trim(line.substr(0, 40))) + "'");
    if (key == "v") {
      three_numbers(rest, path, line_no, "vertex", &s.coords);
      ++s.vertices;
    } else if (key == "vn") {
      // tinyobjloader reads what it can; a NaN normal shaded its triangles black.
      three_numbers(rest, path, line_no, "normal", nullptr);
    } else if (key == "f") {
      int corners = 0;
      for (std::string_view tok = next_token(rest); !tok.empty(); tok = next_token(rest)) {
        const std::string idx(tok.substr(0, tok.find('/')));
        char* e = nullptr;
        const long v = std::strtol(idx.c_str(), &e, 10);
        if (idx.empty() || e != idx.c_str() + idx.size())
          fail(path, line_no, "face index '" + cut_for_message(tok) + "' is not a number");
        if (v == 0 || (v < 0 && 0 - static_cast<std::size_t>(v) > s.vertices))
          fail(path, line_no, "face index " + idx + " out of range (" +
                                  std::to_string(s.vertices) + " vertices so far)");
        if (v > s.max_index) {
          s.max_index = v;
          s.max_index_line = line_no;
        }
        ++corners;
      }
      if (corners < 3) fail(path, line_no, "face with fewer than 3 vertices");
      // tinyobjloader's triangulation takes time quadratic in the corners.
      if (corners > kMaxFaceCorners)
        fail(path, line_no, "face with " + std::to_string(corners) + " corners; at most " +
                                std::to_string(kMaxFaceCorners) + " (triangulate it first)");
      ++s.faces;
    } else if (key == "mtllib") {
      s.mtllibs.emplace_back(trim(rest));
    }
  }
}

// What only the whole file can say.
void scan_end(const Scan& s, const std::string& path) {
  if (s.max_index > 0 && static_cast<std::size_t>(s.max_index) > s.vertices)
    fail(path, s.max_index_line, "face index " + std::to_string(s.max_index) +
                                     " out of range (" + std::to_string(s.vertices) +
                                     " vertices)");
  if (s.faces == 0) fail(path, 0, "no faces (empty or not an OBJ mesh)");
}

// The decimal number the scene file wrote for a value the scene reader keeps
// as a float, in double: the shortest decimal that reads back as that float
// (std::to_chars), which is what the file says whenever it gave at most
// float's 6-9 significant digits. A scale of 0.6 applied as 0.6f moves a
// vertex at 1e6 by 0.024; applied as 0.6, by nothing a float can hold.
double written_value(float x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  *r.ptr = '\0';
  return std::strtod(buf, nullptr);
}

// Whether a triangle has an area: the cross product of two edges is not zero.
bool has_area(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2) {
  const glm::dvec3 e1 = p1 - p0, e2 = p2 - p0;
  return e1.y * e2.z - e1.z * e2.y != 0.0 || e1.z * e2.x - e1.x * e2.z != 0.0 ||
         e1.x * e2.y - e1.y * e2.x != 0.0;
}

// The file's bytes, without a UTF-8 byte order mark (some Windows exporters
// write one); never empty; scanned into `s` piece by piece as they are read,
// so that memory follows the bytes read up to the first bad line. A file
// over kMaxObjBytes is refused before reading (its size), or when it grows
// past it.
std::string read_obj_text(const std::string& path, Scan& s) {
  std::error_code ec;
  if (const auto size = std::filesystem::file_size(path, ec); !ec && size > kMaxObjBytes)
    fail(path, 0, std::to_string(size) + " bytes; an OBJ file may have at most " +
                      std::to_string(kMaxObjBytes >> 20) + " MiB");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, 0, std::string("cannot open file: ") + std::strerror(errno));
  std::string text;  // grown as read (not reserved: a bad line may end it early)
  std::vector<char> buf(1 << 20);
  std::size_t scanned = 0;  // text[0, scanned) holds whole lines, checked
  bool first = true;
  while (in.read(buf.data(), std::streamsize(buf.size())) || in.gcount() > 0) {
    text.append(buf.data(), std::size_t(in.gcount()));
    if (text.size() > kMaxObjBytes)
      fail(path, 0, "over " + std::to_string(kMaxObjBytes >> 20) + " MiB; not a mesh to load");
    if (first && text.size() >= 3) {
      if (text.rfind("\xEF\xBB\xBF", 0) == 0) text.erase(0, 3);
      first = false;
    }
    const std::size_t last = text.rfind('\n');
    if (last != std::string::npos && last + 1 > scanned) {
      scan_lines(s, path, std::string_view(text).substr(scanned, last + 1 - scanned));
      scanned = last + 1;
    }
    // The line not yet ended: binary bytes or an endless line end the read now.
    const std::size_t tail = std::max(scanned, text.size() - std::size_t(in.gcount()));
    for (std::size_t i = tail; i < text.size(); ++i) {
      const unsigned char c = static_cast<unsigned char>(text[i]);
      if (c == 0 || (c < 0x20 && c != '\t' && c != '\r' && c != '\n') || c == 0x7f)
        fail(path, s.line_no + 1, "binary data, not a text OBJ file");
    }
    if (text.size() - scanned > kMaxObjLine)
      fail(path, s.line_no + 1, "line longer than " + std::to_string(kMaxObjLine >> 20) + " MiB");
  }
  if (in.bad()) fail(path, 0, std::string("cannot read file: ") + std::strerror(errno));
  if (first && text == "\xEF\xBB\xBF") text.clear();
  scan_lines(s, path, std::string_view(text).substr(scanned));
  if (text.empty()) fail(path, 0, "file is empty");
  scan_end(s, path);
  return text;
}

// The vertices of `obj` that its faces use, in the file's order, placed
// into `mesh` (exact and positions); `index` maps the file's vertex to its
// place there. A vertex no face uses (a stray point far off) is neither
// kept nor checked: placed with a fit to the faces, it may leave float.
void place_vertices(const ObjFile& obj, float scale, const glm::dvec3& translate,
                    TriangleMesh& mesh, std::vector<unsigned>& index) {
  constexpr unsigned kUnused = ~0u;
  index.assign(obj.coords.size() / 3, kUnused);
  for (const glm::uvec3& tri : obj.triangles)
    for (int k = 0; k < 3; ++k) index[tri[k]] = 0;
  unsigned kept = 0;
  for (unsigned& i : index)
    if (i != kUnused) i = kept++;
  mesh.positions.resize(kept);
  mesh.exact.resize(kept);
  const double sc = written_value(scale);
  const glm::dvec3 tr = translate;  // double, as the scene file wrote it
  for (std::size_t i = 0; i < index.size(); ++i) {
    if (index[i] == kUnused) continue;
    glm::dvec3& x = mesh.exact[index[i]];
    for (int k = 0; k < 3; ++k) x[k] = std::fma(obj.coords[3 * i + k], sc, tr[k]);
    const vec3 p(x);
    mesh.positions[index[i]] = p;
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      fail(obj.path, 0, "vertex " + std::to_string(i + 1) + " is not finite after scale/translate");
  }
}

}  // namespace

ObjFile read_obj(const std::string& path) {
  Scan s;
  const std::string text = read_obj_text(path, s);

  ObjFile obj;
  obj.path = path;
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  for (const std::string& lib : s.mtllibs) {
    // The error_code form: a name over NAME_MAX, a symbolic link loop or a
    // folder that cannot be searched is a message, not an exception.
    std::error_code ec;
    if (std::filesystem::exists(dir / lib, ec)) continue;
    if (ec && ec != std::errc::no_such_file_or_directory)
      fail(path, 0, "material library '" + cut_for_message(lib) + "': " + ec.message());
    obj.warnings.push_back(path + ": material library '" + cut_for_message(lib) +
                           "' not found; materials ignored");
  }

  // Materials come from the scene file, so the library is never read.
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromString(text, std::string(), config)) {
    std::string why = reader.Error();  // may hold several lines, ends in one
    while (!why.empty() && (why.back() == '\n' || why.back() == '\r')) why.pop_back();
    for (std::size_t k; (k = why.find('\n')) != std::string::npos;) why.replace(k, 1, "; ");
    fail(path, 0, "tinyobjloader: " + why);
  }
  const tinyobj::attrib_t& attrib = reader.GetAttrib();

  const std::size_t nv = attrib.vertices.size() / 3;
  // tinyobjloader reads floats (a 1/16 grid at 1e6): the coordinates come
  // from the scan's double reading instead, in the same order.
  if (s.coords.size() != 3 * nv) fail(path, 0, "tinyobjloader read a different vertex count");
  obj.coords = std::move(s.coords);
  const std::size_t nn = attrib.normals.size() / 3;
  obj.normals.resize(nn);
  for (std::size_t i = 0; i < nn; ++i)
    obj.normals[i] = vec3(attrib.normals[3 * i], attrib.normals[3 * i + 1], attrib.normals[3 * i + 2]);

  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const auto& idx = shape.mesh.indices;
    std::size_t at = 0;
    for (unsigned char fv : shape.mesh.num_face_vertices) {
      if (fv != 3) fail(path, 0, "tinyobjloader left a face with " + std::to_string(fv) + " vertices");
      glm::uvec3 tri, nrm;
      bool ok = true, has_n = true;
      for (int k = 0; k < 3; ++k) {
        const int vi = idx[at + k].vertex_index, ni = idx[at + k].normal_index;
        if (vi < 0 || static_cast<std::size_t>(vi) >= nv) ok = false;
        if (ni < 0 || static_cast<std::size_t>(ni) >= nn) has_n = false;
        tri[k] = static_cast<unsigned>(vi);
        nrm[k] = has_n ? static_cast<unsigned>(ni) : 0u;
      }
      at += 3;
      if (!ok) fail(path, 0, "face index out of range");
      obj.triangles.push_back(tri);
      obj.normal_idx.push_back(nrm);
      obj.has_normals.push_back(has_n);
    }
  }
  return obj;
}

TriangleMesh place_obj(const ObjFile& obj, float scale, const glm::dvec3& translate) {
  const std::string& path = obj.path;
  TriangleMesh mesh;
  mesh.warnings = obj.warnings;
  std::vector<unsigned> index;
  place_vertices(obj, scale, translate, mesh, index);
  mesh.normals = obj.normals;
  bool all_normals = !obj.normals.empty();
  for (std::size_t t = 0; t < obj.triangles.size(); ++t) {
    const glm::uvec3 tri(index[obj.triangles[t][0]], index[obj.triangles[t][1]],
                         index[obj.triangles[t][2]]);
    // Of the double-precision vertices: a mesh far from the origin is not
    // flattened by float.
    if (!has_area(mesh.exact[tri[0]], mesh.exact[tri[1]], mesh.exact[tri[2]])) {
      ++mesh.dropped_degenerate;
      continue;
    }
    mesh.triangles.push_back(tri);
    mesh.normal_idx.push_back(obj.normal_idx[t]);
    all_normals = all_normals && obj.has_normals[t];
  }
  if (!all_normals) {
    if (!obj.normals.empty())
      mesh.warnings.push_back(path + ": some faces lack normals; vertex normals ignored");
    mesh.normals.clear();
    mesh.normal_idx.clear();
  }
  if (mesh.dropped_degenerate > 0)
    mesh.warnings.push_back(path + ": dropped " + std::to_string(mesh.dropped_degenerate) +
                            " zero-area triangles");
  if (mesh.triangles.empty()) fail(path, 0, "no triangles with non-zero area");
  return mesh;
}

ObjPlacement fit_obj(const ObjFile& obj, const glm::dvec3& size, const glm::dvec3& base) {
  const auto vertex = [&obj](unsigned i) {
    return glm::dvec3(obj.coords[3 * i], obj.coords[3 * i + 1], obj.coords[3 * i + 2]);
  };
  glm::dvec3 lo(HUGE_VAL), hi(-HUGE_VAL);
  for (const glm::uvec3& tri : obj.triangles) {
    const glm::dvec3 p[3] = {vertex(tri[0]), vertex(tri[1]), vertex(tri[2])};
    if (!has_area(p[0], p[1], p[2])) continue;
    for (const glm::dvec3& q : p) {
      lo = glm::min(lo, q);
      hi = glm::max(hi, q);
    }
  }
  if (!(lo.x <= hi.x)) fail(obj.path, 0, "no triangles with non-zero area");
  // A face with an area spans at least two axes. The scale is kept as a
  // float (the scene's), at most the largest one.
  double s = HUGE_VAL;
  for (int a = 0; a < 3; ++a)
    if (hi[a] > lo[a]) s = std::min(s, size[a] / (hi[a] - lo[a]));
  ObjPlacement fit;
  fit.scale = float(std::min(s, double(std::numeric_limits<float>::max())));
  // As place_obj applies it.
  const double applied = written_value(fit.scale);
  const glm::dvec3 bottom(0.5 * (lo.x + hi.x), lo.y, 0.5 * (lo.z + hi.z));
  fit.translate = base - applied * bottom;
  return fit;
}

TriangleMesh load_obj(const std::string& path, float scale, const glm::dvec3& translate) {
  return place_obj(read_obj(path), scale, translate);
}

}  // namespace whisker
