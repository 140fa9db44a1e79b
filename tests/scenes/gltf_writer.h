#pragma once
// Writes small glTF 2.0 test files: meshes as float32 positions/normals/uvs and uint16 indices
// in one buffer, as .gltf with an external .bin, .gltf with a base64 data URI, or .glb.
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace shadowlab::test {

struct GltfPrimitive {
  std::vector<float> positions;  // xyz per vertex
  std::vector<float> normals;    // xyz per vertex, or empty
  std::vector<float> uvs;        // uv per vertex (glTF: v down), or empty
  std::vector<uint16_t> indices;
  int material = -1;
};

// Builds the JSON and binary buffer as primitives are added; the caller adds nodes, scenes,
// materials, lights and cameras to `json` directly.
struct GltfWriter {
  nlohmann::json json;
  std::vector<uint8_t> bin;

  GltfWriter() {
    json["asset"] = {{"version", "2.0"}};
    json["buffers"] = nlohmann::json::array();
    json["bufferViews"] = nlohmann::json::array();
    json["accessors"] = nlohmann::json::array();
    json["meshes"] = nlohmann::json::array();
  }

  // Appends raw bytes as a buffer view (4-byte aligned) and an accessor over it; returns the
  // accessor index.
  int accessor(const void* data, size_t bytes, int component_type, const char* type, size_t count,
               bool normalized = false) {
    while (bin.size() % 4) bin.push_back(0);
    const size_t offset = bin.size();
    bin.insert(bin.end(), static_cast<const uint8_t*>(data), static_cast<const uint8_t*>(data) + bytes);
    json["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}});
    nlohmann::json a = {{"bufferView", json["bufferViews"].size() - 1},
                        {"componentType", component_type},
                        {"type", type},
                        {"count", count}};
    if (normalized) a["normalized"] = true;
    json["accessors"].push_back(a);
    return int(json["accessors"].size()) - 1;
  }

  // Adds a mesh of the given primitives; returns its index.
  int mesh(const std::vector<GltfPrimitive>& prims, const std::string& name = "") {
    nlohmann::json m;
    if (!name.empty()) m["name"] = name;
    m["primitives"] = nlohmann::json::array();
    for (const GltfPrimitive& p : prims) {
      nlohmann::json jp;
      jp["attributes"]["POSITION"] =
          accessor(p.positions.data(), p.positions.size() * 4, 5126, "VEC3", p.positions.size() / 3);
      if (!p.normals.empty())
        jp["attributes"]["NORMAL"] =
            accessor(p.normals.data(), p.normals.size() * 4, 5126, "VEC3", p.normals.size() / 3);
      if (!p.uvs.empty())
        jp["attributes"]["TEXCOORD_0"] =
            accessor(p.uvs.data(), p.uvs.size() * 4, 5126, "VEC2", p.uvs.size() / 2);
      jp["indices"] = accessor(p.indices.data(), p.indices.size() * 2, 5123, "SCALAR", p.indices.size());
      if (p.material >= 0) jp["material"] = p.material;
      m["primitives"].push_back(jp);
    }
    json["meshes"].push_back(m);
    return int(json["meshes"].size()) - 1;
  }

  static std::string base64(const std::vector<uint8_t>& d) {
    static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < d.size(); i += 3) {
      const uint32_t n = (uint32_t(d[i]) << 16) | (i + 1 < d.size() ? uint32_t(d[i + 1]) << 8 : 0) |
                         (i + 2 < d.size() ? uint32_t(d[i + 2]) : 0);
      out += t[(n >> 18) & 63];
      out += t[(n >> 12) & 63];
      out += i + 1 < d.size() ? t[(n >> 6) & 63] : '=';
      out += i + 2 < d.size() ? t[n & 63] : '=';
    }
    return out;
  }

  // `path` ending in .glb: one GLB file; else .gltf with the buffer in `path`.bin (external) or
  // as a data URI (embed).
  void write(const std::string& path, bool embed = false) {
    nlohmann::json j = json;
    const bool glb = path.size() > 4 && path.substr(path.size() - 4) == ".glb";
    if (glb) {
      j["buffers"] = {{{"byteLength", bin.size()}}};
      std::string text = j.dump();
      while (text.size() % 4) text += ' ';
      std::vector<uint8_t> b = bin;
      while (b.size() % 4) b.push_back(0);
      const uint32_t total = uint32_t(12 + 8 + text.size() + 8 + b.size());
      std::ofstream f(path, std::ios::binary);
      auto u32 = [&](uint32_t v) { f.write(reinterpret_cast<const char*>(&v), 4); };
      u32(0x46546C67u);  // "glTF"
      u32(2);
      u32(total);
      u32(uint32_t(text.size()));
      u32(0x4E4F534Au);  // "JSON"
      f.write(text.data(), std::streamsize(text.size()));
      u32(uint32_t(b.size()));
      u32(0x004E4942u);  // "BIN\0"
      f.write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
      return;
    }
    if (embed) {
      j["buffers"] = {{{"byteLength", bin.size()},
                       {"uri", "data:application/octet-stream;base64," + base64(bin)}}};
    } else {
      const std::string bin_name = path.substr(path.find_last_of('/') + 1) + ".bin";
      j["buffers"] = {{{"byteLength", bin.size()}, {"uri", bin_name}}};
      std::ofstream b(path + ".bin", std::ios::binary);
      b.write(reinterpret_cast<const char*>(bin.data()), std::streamsize(bin.size()));
    }
    std::ofstream f(path);
    f << j.dump(1);
  }
};

// An axis-aligned quad of side `s` in the plane y = h (normal +y), uv over [0, 1]².
inline GltfPrimitive floor_quad(float s, float h, int material = -1) {
  GltfPrimitive p;
  p.positions = {-s, h, -s, s, h, -s, s, h, s, -s, h, s};
  p.normals = {0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0};
  p.uvs = {0, 0, 1, 0, 1, 1, 0, 1};
  p.indices = {0, 2, 1, 0, 3, 2};
  p.material = material;
  return p;
}

// A box [lo, hi] (12 triangles, outward normals per face).
inline GltfPrimitive box(const float lo[3], const float hi[3], int material = -1) {
  GltfPrimitive p;
  p.material = material;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const uint16_t base = uint16_t(p.positions.size() / 3);
      for (int k = 0; k < 4; ++k) {
        float c[3];
        c[axis] = side ? hi[axis] : lo[axis];
        c[u] = (k == 1 || k == 2) ? hi[u] : lo[u];
        c[v] = (k >= 2) ? hi[v] : lo[v];
        p.positions.insert(p.positions.end(), c, c + 3);
        float n[3] = {0, 0, 0};
        n[axis] = side ? 1.0f : -1.0f;
        p.normals.insert(p.normals.end(), n, n + 3);
        p.uvs.push_back(k == 1 || k == 2 ? 1.0f : 0.0f);
        p.uvs.push_back(k >= 2 ? 1.0f : 0.0f);
      }
      // Counter-clockwise seen from outside.
      if (side)
        p.indices.insert(p.indices.end(), {base, uint16_t(base + 1), uint16_t(base + 2), base,
                                           uint16_t(base + 2), uint16_t(base + 3)});
      else
        p.indices.insert(p.indices.end(), {base, uint16_t(base + 2), uint16_t(base + 1), base,
                                           uint16_t(base + 3), uint16_t(base + 2)});
    }
  return p;
}

}  // namespace shadowlab::test
