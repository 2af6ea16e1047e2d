// OBJ loading: the cat, polygons, negative indices, and every kind of bad
// input written here into a temporary directory, each with its message.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <algorithm>

#include <glm/common.hpp>

#include "scene/mesh_io.h"
#include "temp_dir.h"

namespace whisker {
namespace {

namespace fs = std::filesystem;

class MeshIo : public ::testing::Test {
 protected:
  std::string write(const std::string& name, const std::string& text) {
    const std::string p = (dir_ / name).string();
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }

  // The MeshError message for loading `text`, or "" if it loaded.
  std::string error_of(const std::string& text, const std::string& name = "bad.obj") {
    const std::string p = write(name, text);
    try {
      load_obj(p, 1.0f, vec3(0.0f));
    } catch (const MeshError& e) {
      return e.what();
    }
    return "";
  }

  TempDir temp_{"mesh-io"};
  const fs::path dir_ = temp_.path();
};

TEST_F(MeshIo, LoadsTheCatWithAWarningForItsMissingMaterialLibrary) {
  const TriangleMesh m =
      load_obj(WHISKER_ASSETS_DIR "/cat.obj", 0.6f, vec3(0.0f, -10.0f, 0.0f));
  EXPECT_EQ(m.positions.size(), 2247u);
  EXPECT_EQ(m.triangles.size() + m.dropped_degenerate, 3954u);
  EXPECT_EQ(m.dropped_degenerate, 0u);
  ASSERT_FALSE(m.warnings.empty());
  EXPECT_NE(m.warnings[0].find("cat.mtl"), std::string::npos) << m.warnings[0];
  // First vertex of the file, "v  26.7292 34.3821 -4.2469": scale, then
  // translate, rounded once.
  // Read, scaled and translated in double from the written numbers, then
  // rounded once.
  EXPECT_EQ(m.exact[0], glm::dvec3(26.7292 * 0.6, std::fma(34.3821, 0.6, -10.0), -4.2469 * 0.6));
  EXPECT_EQ(m.positions[0], vec3(m.exact[0]));
}

TEST_F(MeshIo, TriangulatesPolygonsAndResolvesNegativeIndices) {
  const std::string p = write("quad.obj",
                              "# a quad and a triangle by negative indices\n"
                              "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                              "f 1 2 3 4\n"
                              "v 0 0 1\n"
                              "f -1 -4 -3\n");
  const TriangleMesh m = load_obj(p, 2.0f, vec3(1.0f, 2.0f, 3.0f));
  ASSERT_EQ(m.triangles.size(), 3u);
  EXPECT_EQ(m.positions.size(), 5u);
  EXPECT_TRUE(m.warnings.empty());
  EXPECT_TRUE(m.normals.empty());
  EXPECT_TRUE(m.normal_idx.empty());
  // p' = p * 2 + (1, 2, 3)
  EXPECT_EQ(m.positions[2], vec3(3.0f, 4.0f, 3.0f));
  EXPECT_EQ(m.positions[4], vec3(1.0f, 2.0f, 5.0f));
  // The quad's two triangles (either diagonal) use only its corners and
  // cover its area, 2 x 2 after scaling.
  double area = 0.0;
  for (int k = 0; k < 2; ++k) {
    const glm::uvec3 t = m.triangles[k];
    ASSERT_LT(std::max({t.x, t.y, t.z}), 4u);
    const glm::dvec3 a(m.positions[t.x]), b(m.positions[t.y]), c(m.positions[t.z]);
    area += 0.5 * std::abs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
  }
  EXPECT_EQ(area, 4.0);
  // -1 -4 -3 after the fifth vertex: vertices 5 2 3.
  EXPECT_EQ(m.triangles[2], glm::uvec3(4, 1, 2));
}

TEST_F(MeshIo, AcceptsCrlfTabsGroupsAndUtf8Comments) {
  const std::string p = write("win.obj",
                              "# caf\xc3\xa9 \xe2\x80\x94 exported on Windows\r\n"
                              "mtllib missing.mtl\r\no obj\r\ng grp\r\ns 1\r\n"
                              "v\t0 0 0\r\nv 1 0 0 # trailing comment\r\nv 0 1 0\r\n"
                              "usemtl red\r\nf 1 2 3\r\n");
  const TriangleMesh m = load_obj(p, 1.0f, vec3(0.0f));
  ASSERT_EQ(m.triangles.size(), 1u);
  EXPECT_EQ(m.positions[1], vec3(1, 0, 0));
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_EQ(m.warnings[0], p + ": material library 'missing.mtl' not found; materials ignored");
}

TEST_F(MeshIo, KeepsVertexNormalsWhenEveryFaceHasThem) {
  const std::string p = write("n.obj",
                              "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvt 0 0\n"
                              "f 1/1/1 2/1/1 3/1/1\n");
  const TriangleMesh m = load_obj(p, 1.0f, vec3(0.0f));
  ASSERT_EQ(m.normals.size(), 1u);
  ASSERT_EQ(m.normal_idx.size(), 1u);
  EXPECT_EQ(m.normals[0], vec3(0, 0, 1));
  EXPECT_EQ(m.normal_idx[0], glm::uvec3(0, 0, 0));
}

TEST_F(MeshIo, DropsAndCountsZeroAreaTriangles) {
  const std::string p = write("deg.obj",
                              "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\n"
                              "f 1 2 3\n"
                              "f 1 2 4\n"    // collinear
                              "f 1 1 3\n");  // repeated vertex
  const TriangleMesh m = load_obj(p, 1.0f, vec3(0.0f));
  EXPECT_EQ(m.triangles.size(), 1u);
  EXPECT_EQ(m.dropped_degenerate, 2u);
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_NE(m.warnings[0].find("dropped 2 zero-area"), std::string::npos);
}

TEST_F(MeshIo, MissingFile) {
  const std::string p = (dir_ / "nowhere.obj").string();
  try {
    load_obj(p, 1.0f, vec3(0.0f));
    FAIL() << "loaded a missing file";
  } catch (const MeshError& e) {
    EXPECT_EQ(std::string(e.what()), p + ": cannot open file: No such file or directory");
  }
}

TEST_F(MeshIo, EmptyFile) {
  const std::string p = (dir_ / "bad.obj").string();
  EXPECT_EQ(error_of(""), p + ": file is empty");
  EXPECT_EQ(error_of("# only a comment\n\n"), p + ": no faces (empty or not an OBJ mesh)");
  EXPECT_EQ(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\n"), p + ": no faces (empty or not an OBJ mesh)");
}

TEST_F(MeshIo, GarbageLine) {
  const std::string p = (dir_ / "bad.obj").string();
  EXPECT_EQ(error_of("v 0 0 0\nv 1 0 0\nhello world\nv 0 1 0\nf 1 2 3\n"),
            p + ":3: unrecognised line 'hello world'");
  EXPECT_EQ(error_of("v 0 0 0\nv 1 zero 0\n"), p + ":2: vertex needs three numbers");
  EXPECT_EQ(error_of("v 0 0\n"), p + ":1: vertex needs three numbers");
  EXPECT_EQ(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n"),
            p + ":4: face index 'x' is not a number");
  EXPECT_EQ(error_of("v 0 0 0\nv 1 0 0\nf 1 2\n"), p + ":3: face with fewer than 3 vertices");
}

TEST_F(MeshIo, IndexOutOfRange) {
  const std::string p = (dir_ / "bad.obj").string();
  EXPECT_EQ(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"),
            p + ":4: face index 4 out of range (3 vertices)");
  EXPECT_EQ(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n"),
            p + ":4: face index -4 out of range (3 vertices so far)");
  EXPECT_EQ(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"),
            p + ":4: face index 0 out of range (3 vertices so far)");
}

TEST_F(MeshIo, NanOrInfCoordinates) {
  const std::string p = (dir_ / "bad.obj").string();
  EXPECT_EQ(error_of("v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n"),
            p + ":2: vertex coordinate is NaN or infinite");
  EXPECT_EQ(error_of("v 0 0 0\nv 1 0 0\nv 0 inf 0\nf 1 2 3\n"),
            p + ":3: vertex coordinate is NaN or infinite");
  EXPECT_EQ(error_of("v 0 0 0\nv 1 0 0\nv 0 1e39 0\nf 1 2 3\n"),
            p + ":3: vertex coordinate is NaN or infinite");
}

TEST_F(MeshIo, BinaryFileNamedObj) {
  std::string bin("v 0 0 0\n");
  for (int i = 0; i < 256; ++i) bin.push_back(static_cast<char>(i));
  EXPECT_EQ(error_of(bin), (dir_ / "bad.obj").string() + ":2: binary data, not a text OBJ file");
}

TEST_F(MeshIo, AllTrianglesDegenerate) {
  EXPECT_EQ(error_of("v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n"),
            (dir_ / "bad.obj").string() + ": no triangles with non-zero area");
}

TEST_F(MeshIo, FitUsesOnlyTheVerticesOfFacesWithAnArea) {
  // One triangle, and far off a vertex no face uses or a face with no area:
  // the fit is the triangle's alone, filling the box (28 tall, it limits).
  const glm::dvec3 size(40.0, 28.0, 40.0), base(0.0, -10.0, 0.0);
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  // (-3e38 x 28 is no float: a vertex no face uses is not kept.)
  for (const std::string extra :
       {"v 1e30 1e30 1e30\nf 1 2 3\n", "v 1e7 1e7 1e7\nf 1 2 3\n", "v -3e38 0 0\nf 1 2 3\n",
        "v 1e7 0 0\nf 1 2 3\nf 4 4 1\n", "f 1 2 3\n"}) {
    const ObjFile obj = read_obj(write("far.obj", tri + extra));
    const ObjPlacement fit = fit_obj(obj, size, base);
    EXPECT_EQ(fit.scale, 28.0f) << extra;
    const TriangleMesh m = place_obj(obj, fit.scale, fit.translate);
    EXPECT_EQ(m.positions.size(), extra.find("f 4") != std::string::npos ? 4u : 3u) << extra;
    ASSERT_EQ(m.triangles.size(), 1u) << extra;
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const glm::uvec3& t : m.triangles)
      for (int k = 0; k < 3; ++k) {
        lo = glm::min(lo, m.exact[t[k]]);
        hi = glm::max(hi, m.exact[t[k]]);
      }
    // Centred at x = z = 0, resting on y = -10.
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(lo[a], glm::dvec3(-14.0, -10.0, 0.0)[a], 1e-12) << extra << " axis " << a;
      EXPECT_NEAR(hi[a], glm::dvec3(14.0, 18.0, 0.0)[a], 1e-12) << extra << " axis " << a;
    }
  }
  // A wide, flat mesh is limited by its width instead; its height is 0.
  const ObjFile flat = read_obj(write("flat.obj", "v 0 5 0\nv 8 5 0\nv 0 5 2\nf 1 2 3\n"));
  const ObjPlacement f = fit_obj(flat, size, base);
  EXPECT_EQ(f.scale, 5.0f);
  EXPECT_EQ(place_obj(flat, f.scale, f.translate).exact[1], glm::dvec3(20.0, -10.0, -5.0));
  // Nothing with an area: nothing to fit, said as place_obj says it.
  const std::string bad = write("line.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  try {
    fit_obj(read_obj(bad), size, base);
    FAIL() << "fitted a mesh without an area";
  } catch (const MeshError& e) {
    EXPECT_EQ(std::string(e.what()), bad + ": no triangles with non-zero area");
  }
}

}  // namespace
}  // namespace whisker
