// The .obj pre-scan on its own: counts, line numbering across line-ending styles, accepted forms.
#include <gtest/gtest.h>

#include "host/scene/obj_validate.h"
#include "scene_test_util.h"

namespace gc {
namespace {

TEST(ObjValidate, CountsElementsAndTriangles)
{
    const ObjScan s = validate_obj_text(
        "mtllib a.mtl b.mtl\nv 0 0 0\nv +1 0 0 1\nv 1 1 0 0.5 0.5 0.5\nv 0 1 0\nvt 0.5\nvt 0 1 0\nvn 0 0 1\n"
        "f 1/1/1 2/2/1 3/1/1 4//1\nf 1 2 3\nl 1 2\n",
        "a.obj");
    EXPECT_EQ(s.positions, 4u);
    EXPECT_EQ(s.texcoords, 2u);
    EXPECT_EQ(s.normals, 1u);
    EXPECT_EQ(s.faces, 2u);
    EXPECT_EQ(s.triangles, 3u);
    EXPECT_EQ(s.material_libraries, (std::vector<std::string>{"a.mtl", "b.mtl"}));
}

TEST(ObjValidate, LineNumbersWithMixedLineEndings)
{
    // Lines: 1 "v" (\r\n), 2 "v" (\r), 3 "v" (\n), 4 empty, 5 bad face.
    test::expect_input_error([] { validate_obj_text("v 0 0 0\r\nv 1 0 0\rv 0 1 0\n\nf 1 2 9\n", "m.obj"); },
                             {"m.obj:5:", "index 9"});
}

TEST(ObjValidate, RejectsTrailingJunkInNumbers)
{
    test::expect_input_error([] { validate_obj_text("v 1.0x 0 0\n", "j.obj"); }, {"j.obj:1:", "1.0x"});
    test::expect_input_error([] { validate_obj_text("v 0 0 0\nf 1/a 1 1\n", "k.obj"); }, {"k.obj:2:", "'a'"});
}

TEST(ObjValidate, BinaryDataRejected)
{
    const std::string text("v 0 0 0\n\0\0\0", 11);
    test::expect_input_error([&] { validate_obj_text(text, "b.obj"); }, {"b.obj", "binary"});
}

}  // namespace
}  // namespace gc
