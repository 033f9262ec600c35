// Mesh files (scene_io/mesh_file.h): one mesh as gmsh .msh 2.2, .msh 4.1 and .obj gives the
// same nodes and triangles; the index forms of .obj; each malformed file's one-line error
// with the file and the line.
#include "scene_io/mesh_file.h"

#include <gtest/gtest.h>

#include <string>

namespace invfree {
namespace {

// A unit square of two triangles, node tags 10 20 30 40, with a point and line elements.
const char* kMsh2 = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
1
2 1 "body"
$EndPhysicalNames
$Nodes
4
10 0 0 0
20 1 0 0
30 1 1 0
40 0 1 0
$EndNodes
$Elements
4
1 15 2 0 1 10
2 1 2 0 1 10 20
3 2 2 1 1 10 20 30
4 2 2 1 1 10 30 40
$EndElements
)";

const char* kMsh4 = R"($MeshFormat
4.1 0 8
$EndMeshFormat
$Entities
1 0 0 1
1 0 0 0 0
1 0 0 0 1 1 0 0
$EndEntities
$Nodes
2 4 10 40
0 1 0 1
10
0 0 0
2 1 0 3
20
30
40
1 0 0
1 1 0
0 1 0
$EndNodes
$Elements
2 3 1 3
1 1 1 1
9 10 20
2 1 2 2
1 10 20 30
2 10 30 40
$EndElements
)";

const char* kObj = R"(# a unit square
o square
v 0 0 0
v 1 0 0
v 1 1 0
vt 0 0
vn 0 0 1
v 0 1 0
s off
f 1 2 3
f 1/1 3/1 4/1
)";

ShapeFile ok(bool msh, const std::string& text) {
  ShapeFile out;
  EXPECT_EQ(msh ? parse_msh(text, "box.msh", out) : parse_obj(text, "box.obj", out), "") << text;
  return out;
}
std::string msh_error(const std::string& text) {
  ShapeFile out;
  return parse_msh(text, "box.msh", out);
}
std::string obj_error(const std::string& text) {
  ShapeFile out;
  return parse_obj(text, "box.obj", out);
}

TEST(MeshFile, SameMeshFromMsh2Msh4AndObj) {
  const ShapeFile a = ok(true, kMsh2);
  ASSERT_EQ(a.nodes.size(), 4u);
  EXPECT_EQ(a.nodes[2], Vec2(1, 1));
  ASSERT_EQ(a.triangles.size(), 2u);
  EXPECT_EQ(a.triangles[0], (std::array<int, 3>{0, 1, 2}));
  EXPECT_EQ(a.triangles[1], (std::array<int, 3>{0, 2, 3}));
  EXPECT_TRUE(a.loops.empty());
  EXPECT_EQ(ok(true, kMsh4), a);
  EXPECT_EQ(ok(false, kObj), a);
  // Windows line ends change nothing.
  std::string crlf;
  for (char c : std::string(kMsh2)) (c == '\n' ? crlf += "\r\n" : crlf += c);
  EXPECT_EQ(ok(true, crlf), a);
}

TEST(MeshFile, ObjIndexForms) {
  const std::string v = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
  const ShapeFile a = ok(false, kObj);
  EXPECT_EQ(ok(false, v + "f 1/1/1 2/2/2 3/3/3\nf 1//1 3//1 4//1\n"), a);
  EXPECT_EQ(ok(false, v + "f -4 -3 -2\nf -4/1 -2 -1//3\n"), a);
  // A face may name a vertex given later.
  EXPECT_EQ(ok(false, "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\nf 1 3 4\nv 0 1 0\n"), a);
  // w and colours after x y z are allowed; z within 1e-12 of the size counts as 0.
  EXPECT_EQ(ok(false, "v 0 0 0 1\nv 1 0 1e-13\nv 1 1 0 0.5 0.5 0.5\nv 0 1 0\nf 1 2 3\nf 1 3 4\n")
                .triangles,
            a.triangles);
}

TEST(MeshFile, MshErrorsNameTheLine) {
  EXPECT_EQ(msh_error("$MeshFormat\n4.1 1 8\n$EndMeshFormat\n"),
            "box.msh: binary .msh is not supported; save as ASCII");
  EXPECT_EQ(msh_error("$MeshFormat\n4 0 8\n$EndMeshFormat\n"),
            "box.msh:2: unsupported .msh version \"4\" (2.x or 4.1; gmsh saves either with "
            "-format msh22 or msh41)");
  std::string bad = kMsh2;
  bad.replace(bad.find("30 1 1 0"), 8, "30 1 1");
  EXPECT_EQ(msh_error(bad), "box.msh:12: expected 4 numbers in a node line (tag x y z)");
  bad = kMsh2;
  bad.replace(bad.find("20 1 0 0"), 8, "20 1 0 0.3");
  EXPECT_EQ(msh_error(bad), "box.msh:11: node 20 has z = 0.3 (the mesh must lie in z = 0)");
  bad = kMsh2;
  bad.replace(bad.find("4 2 2 1 1 10 30 40"), 18, "4 3 2 1 1 10 20 30 40");
  EXPECT_EQ(msh_error(bad),
            "box.msh:20: element type 3 (4-node quadrangle) is not supported: only 3-node "
            "triangles (type 2), with points and lines ignored");
  bad = kMsh2;
  bad.replace(bad.find("4 2 2 1 1 10 30 40"), 18, "4 2 2 1 1 10 30 99");
  EXPECT_EQ(msh_error(bad), "box.msh:20: node 99 is not in $Nodes");
  bad = kMsh2;
  bad.replace(bad.find("4 2 2 1 1 10 30 40"), 18, "4 2 2 1 1 10 30");
  EXPECT_EQ(msh_error(bad), "box.msh:20: a triangle (type 2) needs 3 node tags, got 2");
  bad = kMsh2;
  bad.replace(bad.find("40 0 1 0"), 8, "10 0 1 0");
  EXPECT_EQ(msh_error(bad), "box.msh:13: node tag 10 appears twice");
  bad = kMsh2;
  bad.replace(bad.find("$EndNodes"), 9, "$EndNode");
  EXPECT_EQ(msh_error(bad), "box.msh:14: expected $EndNodes, got \"$EndNode\"");
  EXPECT_EQ(msh_error("$Nodes\n"), "box.msh:1: expected $MeshFormat first");
  EXPECT_EQ(msh_error(""), "box.msh: not a gmsh .msh file (no $MeshFormat)");
  EXPECT_EQ(msh_error("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n0\n$EndNodes\n"),
            "box.msh: no $Elements section");
  EXPECT_EQ(msh_error("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n0\n$EndNodes\n$Elements\n0\n"
                      "$EndElements\n"),
            "box.msh: no triangles (element type 2)");
  EXPECT_EQ(msh_error("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2\n1 0 0 0\n"),
            "box.msh:6: expected 4 numbers in a node line (tag x y z)");
  EXPECT_EQ(msh_error("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 nan 0 0\n"),
            "box.msh:6: expected 4 numbers in a node line (tag x y z)");
  // v4: block counts.
  bad = kMsh4;
  bad.replace(bad.find("2 4 10 40"), 9, "2 5 10 40");
  EXPECT_EQ(msh_error(bad), "box.msh:20: the node blocks hold 4 nodes, the header says 5");
  bad = kMsh4;
  bad.replace(bad.find("1 1 0\n"), 5, "1 1");
  EXPECT_EQ(msh_error(bad), "box.msh:19: expected 3 numbers in a node line (x y z)");
  bad = kMsh4;
  bad.replace(bad.find("$Elements\n2 3 1 3"), 17, "$Elements\n2 3 1");
  EXPECT_EQ(msh_error(bad),
            "box.msh:23: expected 4 numbers: numEntityBlocks numElements minElementTag "
            "maxElementTag");
  bad = kMsh4;
  bad.replace(bad.find("$EndEntities"), 12, "");
  EXPECT_EQ(msh_error(bad), "box.msh: the file ends before $EndEntities");
  for (const std::string& e : {msh_error(bad), msh_error("$MeshFormat\nx\n")})
    EXPECT_EQ(e.find('\n'), std::string::npos);
}

TEST(MeshFile, ObjErrorsNameTheLine) {
  EXPECT_EQ(obj_error("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"),
            "box.obj:5: a face with 4 vertices: only triangles are read (triangulate the mesh "
            "first)");
  EXPECT_EQ(obj_error("v 0 0 0\nv 1 0 0\nv 1 1 0.3\nf 1 2 3\n"),
            "box.obj:3: vertex 3 has z = 0.3 (the mesh must lie in z = 0)");
  EXPECT_EQ(obj_error("v 0 0\n"),
            "box.obj:1: expected 'v x y z' (3 numbers, or 4 with w, or 6 with a colour)");
  EXPECT_EQ(obj_error("v 0 0 0\nf 1 2\n"), "box.obj:2: a face needs 3 vertices, got 2");
  EXPECT_EQ(obj_error("v 0 0 0\nf 1 0 1\n"),
            "box.obj:2: expected a vertex index (1, 1/2, 1/2/3, 1//3 or negative), got \"0\"");
  EXPECT_EQ(obj_error("v 0 0 0\nf 1 -2 1\n"),
            "box.obj:2: vertex index -2 points before the first vertex (1 so far)");
  EXPECT_EQ(obj_error("v 0 0 0\nv 1 0 0\n\nf 1 2 3\n"),
            "box.obj:4: vertex 3 does not exist (the file has 2)");
  EXPECT_EQ(obj_error("v 0 0 0\n"), "box.obj: no triangles (no 'f' lines)");
  EXPECT_EQ(obj_error("v 0 0 0\ncurv 0 1\n"),
            "box.obj:2: unknown statement \"curv\" (read: v, f; ignored: vt, vn, vp, o, g, s, l, "
            "usemtl, mtllib, #)");
}

}  // namespace
}  // namespace invfree
