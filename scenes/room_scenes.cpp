// The built-in scenes "room100k" and "room1m": the benchmark room rebuilt procedurally.
#include "scenes/room_scenes.h"

#include <string>

#include "scenes/mesh_builders.h"

namespace shadowlab {
namespace {

// The benchmark room of assets/bench/room100k.obj, rebuilt procedurally (layout read
// off the OBJ's vertices group by group: sphere centre = mean of the unique vertices, radius =
// their mean distance to it; torus centre = vertex mean, axis = least-variance direction,
// major/minor radius = mid-point/half-width of the vertices' distances from the axis).
//  - mesh 0 "room" (12 triangles, as the OBJ's `g room`): a 60 × 60 m ground quad at y = 0
//    (x, z in [-30, 30], front +y) and a 20 × 8 × 20 m room on it (x, z in [-10, 10], y in
//    [0, 8]): ceiling and four walls facing inward, one quad each, no floor of its own.
//  - meshes 1..64 "object0".."object63", alternating: even objects are UV spheres (poles on
//    ±y, φ = 0 on +x), odd ones tori; tables kRoomSpheres and kRoomTori, in OBJ order. The
//    spheres with centre y = radius rest on the ground; the rest float inside the room.
//  - point light (0, 4, 0), radius 0 (hard), near 0.05, far 40 (the ground's corners, 42.6 m
//    away, lie beyond it, as in the OBJ); camera eye (0, 4.5, 9.5), target (0, 3, 0), up +y,
//    fov_y 60°, 1024 × 768, near 0.05, far 100 (the OBJ loader's camera defaults).
// Differences from the OBJ: the OBJ's tori wind inward (its spheres and room do not); here
// every torus faces outward like every builder (only back-face culling sees the difference);
// vertex positions agree with the OBJ's to its 5–6 printed digits, the diagonal chosen for each
// quad of a sphere may differ.
struct RoomSphere {
  vec3 centre;
  float radius;
};
struct RoomTorus {
  vec3 centre;
  vec3 axis;  // unit; u = normalize(cross(axis, +y)) is the OBJ's φ = 0 direction
  float major, minor;
};
// object0, object2, ..., object62.
const RoomSphere kRoomSpheres[32] = {
    {{7.05766f, 5.99936f, -3.19129f}, 0.64904f},
    {{-2.22101f, 0.94565f, -2.43372f}, 0.94565f},
    {{-8.40729f, 0.47481f, 4.90868f}, 0.47481f},
    {{-8.51362f, 3.94954f, 3.95608f}, 1.08930f},
    {{7.64388f, 6.22235f, 0.81049f}, 0.54411f},
    {{5.54148f, 1.12566f, -5.60998f}, 1.12566f},
    {{-4.59538f, 1.17261f, 5.79963f}, 1.17261f},
    {{6.87554f, 0.58039f, 0.48512f}, 0.58039f},
    {{6.60277f, 4.17294f, -2.26857f}, 0.55484f},
    {{-6.09851f, 5.01874f, -5.26527f}, 0.95489f},
    {{3.02921f, 6.55882f, -3.20771f}, 0.93471f},
    {{-6.39270f, 6.48204f, -6.76092f}, 0.85385f},
    {{-8.89852f, 0.86582f, 2.84802f}, 0.86582f},
    {{-2.32956f, 4.93387f, -1.03051f}, 0.66171f},
    {{-4.73246f, 1.84237f, 0.88975f}, 1.18998f},
    {{-3.09534f, 6.12766f, 6.12116f}, 0.96992f},
    {{-5.40361f, 5.26698f, 8.80599f}, 0.60808f},
    {{-6.25961f, 5.52080f, -3.17815f}, 0.98921f},
    {{8.27009f, 0.76136f, 5.39434f}, 0.76136f},
    {{-1.07971f, 1.93331f, 0.90642f}, 0.58110f},
    {{4.07206f, 2.96232f, -7.00198f}, 0.63279f},
    {{-1.63382f, 0.84515f, 4.51040f}, 0.84515f},
    {{3.10504f, 2.51699f, -8.37551f}, 0.79544f},
    {{7.90783f, 0.81801f, 7.58436f}, 0.81801f},
    {{-1.05310f, 0.57992f, 7.18968f}, 0.57992f},
    {{-2.51333f, 0.53335f, 8.32055f}, 0.53335f},
    {{-7.56631f, 6.78338f, 1.39318f}, 0.65965f},
    {{-3.41501f, 6.29013f, -1.05375f}, 0.83543f},
    {{1.01577f, 4.70027f, -4.68396f}, 0.58329f},
    {{-6.75049f, 3.35197f, -3.59850f}, 0.57788f},
    {{-3.42070f, 2.05925f, -7.56014f}, 0.53324f},
    {{-3.91042f, 0.93445f, -4.25717f}, 0.93445f},
};
// object1, object3, ..., object63.
const RoomTorus kRoomTori[32] = {
    {{-5.44995f, 1.06138f, 8.44250f}, {-0.07174f, 0.85446f, 0.51454f}, 0.79613f, 0.26526f},
    {{2.78756f, 0.85684f, 6.33706f}, {-0.23092f, -0.60497f, 0.76202f}, 0.56338f, 0.29347f},
    {{-7.94026f, 0.58828f, -3.84578f}, {0.16555f, -0.98479f, -0.05271f}, 0.44206f, 0.14622f},
    {{-2.68811f, 0.87004f, -0.33238f}, {0.80130f, -0.52281f, -0.29083f}, 0.67532f, 0.19472f},
    {{3.84578f, 6.98641f, -6.95820f}, {-0.45568f, -0.62351f, 0.63529f}, 0.36444f, 0.15918f},
    {{3.26160f, 1.54199f, 0.21275f}, {0.06055f, 0.99787f, 0.02427f}, 0.59168f, 0.31162f},
    {{4.62044f, 4.52506f, 4.36054f}, {0.43800f, -0.89576f, -0.07599f}, 0.72555f, 0.31542f},
    {{5.13324f, 0.97443f, 0.50967f}, {-0.50828f, -0.50283f, -0.69915f}, 0.73404f, 0.24039f},
    {{0.64726f, 2.17733f, -0.74144f}, {0.18094f, -0.95999f, 0.21372f}, 0.35250f, 0.18355f},
    {{-2.27997f, 1.11006f, -8.62760f}, {-0.96302f, 0.26940f, -0.00458f}, 0.72524f, 0.38482f},
    {{8.55053f, 0.72631f, -7.54130f}, {-0.08305f, 0.85872f, 0.50567f}, 0.51192f, 0.21439f},
    {{9.00628f, 1.86872f, -4.07503f}, {0.15766f, -0.27967f, -0.94706f}, 0.59768f, 0.18988f},
    {{7.83260f, 4.25415f, 8.42927f}, {-0.16457f, -0.95266f, 0.25566f}, 0.80401f, 0.37705f},
    {{-6.16401f, 1.70580f, -7.37241f}, {0.00250f, -0.62500f, 0.78062f}, 0.52284f, 0.23789f},
    {{-3.13512f, 0.87816f, 2.09221f}, {0.96051f, -0.02954f, 0.27666f}, 0.63042f, 0.24774f},
    {{7.72849f, 6.23590f, 7.13771f}, {0.06156f, 0.97907f, 0.19399f}, 0.82022f, 0.20524f},
    {{-6.37976f, 3.54725f, 2.00745f}, {-0.63902f, 0.09391f, 0.76343f}, 0.61219f, 0.21976f},
    {{0.39960f, 0.45192f, -0.89742f}, {0.20120f, 0.97932f, 0.02108f}, 0.33506f, 0.11686f},
    {{7.58942f, 3.11471f, -0.16785f}, {-0.27980f, 0.46041f, -0.84246f}, 0.61204f, 0.29529f},
    {{0.87740f, 1.51764f, 1.90445f}, {-0.23587f, -0.81667f, 0.52670f}, 0.49048f, 0.18434f},
    {{-0.05863f, 1.18554f, 5.39758f}, {0.82678f, -0.56200f, -0.02430f}, 0.34869f, 0.17219f},
    {{2.79043f, 4.68749f, 0.08449f}, {-0.71032f, -0.11648f, 0.69417f}, 0.66239f, 0.18196f},
    {{0.76898f, 4.12172f, -7.63928f}, {-0.41584f, -0.25800f, -0.87207f}, 0.37300f, 0.17428f},
    {{-8.24723f, 4.91821f, -5.86197f}, {-0.70774f, -0.61858f, -0.34128f}, 0.57725f, 0.16817f},
    {{-2.90066f, 0.61975f, -6.38268f}, {-0.15507f, -0.98779f, 0.01516f}, 0.47314f, 0.14661f},
    {{-0.07983f, 4.95248f, -3.42088f}, {0.00126f, -0.81104f, 0.58498f}, 0.48393f, 0.14036f},
    {{0.10631f, 0.93435f, -3.76216f}, {0.72820f, -0.36130f, -0.58240f}, 0.70883f, 0.22553f},
    {{-1.34410f, 0.74558f, -6.89178f}, {-0.50294f, 0.01053f, 0.86425f}, 0.51383f, 0.23175f},
    {{3.02754f, 4.55003f, -7.20990f}, {0.63202f, -0.67434f, 0.38185f}, 0.41644f, 0.12651f},
    {{2.05066f, 4.28597f, -2.16632f}, {-0.88989f, -0.11052f, 0.44259f}, 0.84679f, 0.25228f},
    {{-3.85390f, 2.84555f, -2.11657f}, {-0.33476f, -0.48565f, 0.80751f}, 0.36903f, 0.16314f},
    {{6.67501f, 6.24713f, -5.13162f}, {0.12336f, 0.89268f, -0.43348f}, 0.61591f, 0.30896f},
};

// The room with spheres of sphere_segments × sphere_rings (2·s·(r − 1) triangles) and tori of
// torus_major × torus_minor segments (2·M·m triangles).
Scene make_room_scene(const std::string& name, int sphere_segments, int sphere_rings,
                      int torus_major, int torus_minor) {
  Scene s;
  s.name = name;
  s.meshes.reserve(65);
  s.materials.reserve(65);
  {
    Mesh& room = new_mesh(s, "room", vec3(0.75f));
    add_grid_quad(room, vec3(-30, 0, -30), vec3(0, 0, 60), vec3(60, 0, 0), 1, 1);  // ground, +y
    add_grid_quad(room, vec3(-10, 8, -10), vec3(20, 0, 0), vec3(0, 0, 20), 1, 1);  // ceiling, -y
    add_grid_quad(room, vec3(-10, 0, -10), vec3(20, 0, 0), vec3(0, 8, 0), 1, 1);   // z = -10, +z
    add_grid_quad(room, vec3(-10, 0, 10), vec3(0, 8, 0), vec3(20, 0, 0), 1, 1);    // z = +10, -z
    add_grid_quad(room, vec3(-10, 0, -10), vec3(0, 8, 0), vec3(0, 0, 20), 1, 1);   // x = -10, +x
    add_grid_quad(room, vec3(10, 0, -10), vec3(0, 0, 20), vec3(0, 8, 0), 1, 1);    // x = +10, -x
  }
  for (int i = 0; i < 32; ++i) {
    const RoomSphere& sp = kRoomSpheres[i];
    add_uv_sphere(new_mesh(s, "object" + std::to_string(2 * i), vec3(0.35f, 0.55f, 0.75f)),
                  sp.centre, sp.radius, sphere_segments, sphere_rings);
    const RoomTorus& t = kRoomTori[i];
    add_torus(new_mesh(s, "object" + std::to_string(2 * i + 1), vec3(0.75f, 0.50f, 0.30f)),
              t.centre, t.axis, t.major, t.minor, torus_major, torus_minor);
  }
  s.light.position = vec3(0.0f, 4.0f, 0.0f);
  s.light.radius = 0.0f;
  s.light.near = 0.05f;
  s.light.far = 40.0f;
  s.camera.eye = vec3(0.0f, 4.5f, 9.5f);
  s.camera.target = vec3(0.0f, 3.0f, 0.0f);
  s.camera.up = vec3(0.0f, 1.0f, 0.0f);
  s.camera.fov_y_deg = 60.0f;
  s.camera.near = 0.05f;
  s.camera.far = 100.0f;
  s.camera.width = 1024;
  s.camera.height = 768;
  return s;
}

}  // namespace

// The OBJ's tessellation: 99,852 triangles.
Scene make_room100k_scene() { return make_room_scene("room100k", 40, 20, 40, 20); }
// 12 + 32·15,360 + 32·15,872 = 999,436 triangles.
Scene make_room1m_scene() { return make_room_scene("room1m", 128, 61, 128, 62); }

}  // namespace shadowlab
