#pragma once
// Strict line-by-line check of OBJ and MTL text, run before tinyobjloader parses it:
// tinyobjloader reads non-numeric tokens, "nan" and missing coordinates as 0 without a
// warning, and skips lines it does not know, so a garbage file would load as a wrong model.
// Internal to the OBJ loader (scenes/obj_loader.cpp); exposed for tests.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace shadowlab {

struct ObjTextSummary {
  size_t positions = 0;            // `v` statements
  size_t normals = 0;              // `vn` statements
  size_t texcoords = 0;            // `vt` statements
  size_t faces = 0;                // `f` statements
  size_t triangles = 0;            // sum of (corners - 2) over faces
  bool has_mtllib = false;         // some `mtllib` statement
  std::vector<std::string> notes;  // harmless oddities (ignored statements)
};

// Throws InputError(path, "line N: ...") on: an unknown statement; a `v` without 3..7
// numbers, `vn` without 3, `vt` without 1..3; a token that is not a number; a NaN, infinite or
// float-overflowing position ("vertex K (line N) has a NaN or infinite ..."), normal or
// texcoord; a face with < 3 corners, a malformed corner, index 0 or an index out of range;
// `usemtl`/`mtllib` without a name.
ObjTextSummary check_obj_text(const std::string& path, std::string_view text);

// Throws InputError(path, "line N: ...") when a statement the loader uses (newmtl, Kd, d, Tr)
// is missing its argument or has a non-numeric/non-finite one.
void check_mtl_text(const std::string& path, std::string_view text);

}  // namespace shadowlab
