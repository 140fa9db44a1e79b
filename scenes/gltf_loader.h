#pragma once
// glTF 2.0 loading (.gltf with external or data-URI buffers, and .glb), through tinygltf.
//
// Geometry
// - The default scene (`scene`, else scene 0) and its whole node hierarchy: a node's local
//   transform is its `matrix` (column-major) or T·R·S; world = parent world × local. A node
//   reachable twice (a cycle, or a node with two parents) is an error.
// - Every primitive of every mesh instance becomes one Mesh named "<mesh name or mesh#i>/<p>":
//   positions and normals transformed to world space (normals by the inverse transpose, then
//   normalised; recomputed, area-weighted, when the primitive has none or any is zero or not
//   finite), indices as given (or 0, 1, 2, … without an index accessor). A negative-determinant
//   transform reverses each triangle's winding, so the front stays counter-clockwise.
// - Triangle primitives only (mode 4, the default); any other mode is an error naming the mesh.
// - Accessors are checked against their buffer views and buffers (offsets, strides, counts,
//   component types); sparse accessors are not supported (an error). Indices must be below the
//   vertex count; positions finite.
//
// Materials (metallic-roughness core; other extensions are ignored)
// - The baseColorTexture (sRGB-decoded) is the material's colour texture with baseColorFactor.rgb
//   as its factor (Material::color_texture); albedo = the factor × the texture's mean linear
//   colour, as for OBJ's map_Kd.
// - alphaMode MASK: the baseColorTexture's alpha × baseColorFactor.a becomes the alpha texture
//   with cutoff alphaCutoff (default 0.5), used by the camera pass, every shadow-map pass and
//   Embree's filters; without a texture, a 1×1 alpha texture of baseColorFactor.a. BLEND is
//   taken as MASK at cutoff 0.5, with a note. OPAQUE ignores alpha.
// - glTF texture coordinates have v down from the image's top; shadowlab's have v up
//   (core/texture.h), so v is stored as 1 − v. TEXCOORD_n of the texture's texCoord is read.
// - Images larger than 16384 × 16384 texels are refused before decoding.
//
// Lights (KHR_lights_punctual) and cameras
// - Lights are those placed by nodes, in node order (depth first from the scene's roots). A
//   point light sets the light's position (the node's world origin), its far distance from
//   `range` when given, and its radius from the light's `extras.radius` when given (else 0, a
//   hard light; --light-radius overrides). A spot light becomes the slide projector with the
//   "spot" slide, aimed down the node's −z, vertical field of view 2 × outerConeAngle, aspect 1.
//   Directional lights are not supported: an error when picked.
// - Cameras are perspective cameras placed by nodes, in node order: eye at the node's origin,
//   looking down its −z with up its +y, yfov, znear and zfar (when given), and the image width
//   from aspectRatio at the default height 768. An orthographic camera is an error when picked.
// - GltfChoice picks the light and camera (default the first of each); with none in the file,
//   make_gltf_scene frames them from the bounds as for OBJ and says so in a note.
//
// Errors: InputError(path, reason) — unreadable file, JSON or schema failures (tinygltf's first
// error line), a missing buffer file, every check above, a scene without triangles, a picked
// light or camera that does not exist.
#include <string>
#include <vector>

#include "core/scene.h"

namespace shadowlab {

struct GltfChoice {
  int light = 0;   // index among the placed lights (--light N)
  int camera = 0;  // index among the placed cameras (--camera N)
};

// What a file held, for the notes and for framing.
struct GltfContents {
  int lights = 0, cameras = 0;  // placed in the scene
  bool light_used = false, camera_used = false;
  std::string light_text, camera_text;  // which one was used, for the output
};

// Loads the glTF at `path` into a Scene (meshes, materials, alpha textures; light and camera as
// above, else left at their defaults). Notes (harmless oddities) go to *notes when given, else
// to stderr as "warning: <path>: <note>".
Scene load_gltf_scene(const std::string& path, const GltfChoice& choice, GltfContents* contents,
                      std::vector<std::string>* notes = nullptr);

// load_gltf_scene, then the camera and/or light framed from the bounds when the file has none
// (scenes/scene_library.h frame_from_bounds), with a note saying so and which light and camera
// were used; validates the scene.
Scene make_gltf_scene(const std::string& path, const GltfChoice& choice,
                      std::vector<std::string>* notes = nullptr);

// True for a path ending in .gltf or .glb (any case).
bool is_gltf_path(const std::string& path);

}  // namespace shadowlab
