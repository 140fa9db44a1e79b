#pragma once
// Wavefront OBJ + MTL loading (through tinyobjloader, behind a strict text check, because
// tinyobjloader silently reads garbage numbers, "nan" and missing coordinates as 0).
//
// Geometry rules
// - Polygons are triangulated (quads split along the shorter diagonal, larger polygons by ear
//   clipping, both by tinyobjloader).
// - One Mesh per (shape, material) pair, in file order; a shape is a `g`/`o` group. The mesh is
//   named after the shape (the file stem for unnamed shapes), with "/<material>" appended when
//   the shape uses several materials.
// - Corners are de-indexed into per-mesh vertex arrays; identical (v, vn, vt) triples are
//   welded into one vertex.
// - Normals: the file's normals (normalised) when every corner of the mesh has one; otherwise
//   (none, some missing, or a zero-length one) all normals of the mesh are recomputed with
//   compute_vertex_normals (area-weighted, smooth over welded vertices).
// - UVs: kept when every corner has one; empty when none has; a mix gets (0, 0) for the
//   missing ones (with a note).
//
// Material rules
// - albedo = Kd × (when map_Kd is present) the mean linear colour of map_Kd over the texels
//   that pass the alpha test; map_Kd (linear RGBA) is also the colour texture with Kd as its
//   factor (Material::color_texture, for the shaded pictures).
//   A material with map_Kd but no Kd line gets Kd = 0.6 (tinyobjloader's default).
// - Alpha (cutout) texture: map_d when present — its alpha channel if the file has one,
//   otherwise its grey (red) channel, as stored. Without map_d, map_Kd becomes the alpha
//   texture when its file has an alpha channel with some value < 1. An alpha texture whose
//   alpha is 1 everywhere is dropped (the material takes the opaque fast path).
// - The dissolve value `d` (and `Tr`) is ignored: some MTLs set d 0 on opaque materials, and
//   shadowlab has no translucency. d < 1 gives a note, never a dropped material.
// - alpha_cutoff = 0.5. Texture paths are resolved relative to the folder of the MTL that
//   names them; MTL paths relative to the OBJ's folder.
// - Faces without a material (no usemtl, or no MTL at all) use one appended material named
//   "default" (albedo 0.8).
//
// Errors (InputError, `where` = the offending file): a missing/unreadable OBJ, MTL or texture;
// malformed OBJ lines (unknown statements, non-numeric or missing numbers, bad face indices,
// faces with < 3 corners, line numbers in the reason); a NaN/Inf/overflowing vertex (reason
// names the 1-based vertex number and the line); a usemtl naming a material that the loaded
// MTLs lack; an alpha-textured mesh without texture coordinates; a model without triangles.
// Harmless oddities (ignored `l`/`p`/curve statements, `d` < 1, recomputed normals) are notes.
// A UTF-8 byte-order mark at the start of an OBJ or MTL is skipped.
#include <optional>
#include <string>
#include <vector>

#include "core/scene.h"

namespace shadowlab {

// Loads the OBJ at `path` into a Scene holding its meshes, the materials they use and their
// alpha textures; name = the file stem. Light and camera keep their defaults (see
// make_obj_scene for framing). Notes (harmless oddities) are appended to *notes when given,
// else printed to stderr as "warning: <path>: <note>".
Scene load_obj_scene(const std::string& path, std::vector<std::string>* notes = nullptr);

// A light and camera written in an OBJ's leading comment lines, as in bench/room100k.obj:
//   # ... point light (0,4,0), near 0.05 far 40
//   # camera eye (0,4.5,9.5) target (0,3,0) up (0,1,0) vertical fov 60 deg, 1024x768
// Only comment lines before the first statement are searched. Missing parts stay unset.
struct ObjViewHeader {
  std::optional<PointLight> light;  // radius 0 (a point light), near/far when given
  std::optional<Camera> camera;     // eye and target required; up (+y), fov, WxH when given
};
// Throws InputError(path, "cannot open: ...") when the file cannot be read.
ObjViewHeader read_obj_view_header(const std::string& path);

}  // namespace shadowlab
