// A pass over the .obj text before tinyobjloader sees it. tinyobjloader is forgiving in ways
// that hide broken files: "nan", "inf" and garbage parse as 0, index 0 and out-of-range
// indices are wrapped or skipped silently. This scan rejects them with the line number.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace gc {

struct ObjScan {
    std::size_t positions = 0;      // v lines
    std::size_t texcoords = 0;      // vt lines
    std::size_t normals = 0;        // vn lines
    std::size_t faces = 0;          // f lines
    std::size_t triangles = 0;      // after fan triangulation
    std::vector<std::string> material_libraries; // file names from mtllib lines, in order
};

// Throws InputError "<file_name>:<line>: <what>" for: non-numeric or non-finite v/vt/vn
// values, missing coordinates, face indices that are 0 or outside the elements declared so
// far (negative indices count back from the last one), faces with fewer than 3 corners, and
// NUL bytes (a binary file). `file_name` is only used in messages.
ObjScan validate_obj_text(std::string_view text, const std::string& file_name);

// The same check for a .mtl library: the numbers of Ka/Kd/Ks/Ke/Tf (three, or one grey value),
// Ns/Ni/d/Tr (one) must be finite numbers; NUL bytes are refused. Throws InputError
// "<file_name>:<line>: <what>".
void validate_mtl_text(std::string_view text, const std::string& file_name);

}  // namespace gc
