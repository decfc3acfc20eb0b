// Writes deep-nesting seeds into the seed corpora of the JSON-based targets:
//   write_nesting_seeds GLTF_SEED_FOLDER MANIFEST_SEED_FOLDER
// Nesting this deep crashed recursive loaders (a glTF node chain 20,000 deep, `extras` and a
// manifest nested 100,000 deep), but the files are several hundred KB: more than the mutations
// reach from small seeds, and more than is worth committing. Generated here, they are replayed
// by every CI run and mutated from (run_ci.sh gives these targets a 1 MB input limit).
#include <cstdio>
#include <fstream>
#include <string>

namespace {

// One triangle in a base64 data URI (three float positions, three 16-bit indices).
constexpr const char* triangle_buffers =
    R"("meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
"accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
  "min": [0, 0, 0], "max": [1, 1, 0]},
 {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
"bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
 {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
"buffers": [{"byteLength": 44, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA="}])";

// Node k's only child is node k + 1; the last node holds the triangle.
std::string node_chain(int depth) {
  std::string text = R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], )";
  text += R"("nodes": [)";
  for (int k = 0; k + 1 < depth; ++k) text += "{\"children\":[" + std::to_string(k + 1) + "]},";
  text += R"({"mesh": 0}], )";
  return text + triangle_buffers + "}";
}

std::string deep_extras(int depth) {
  std::string text = R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], )";
  text += R"("nodes": [{"mesh": 0, "extras": )";
  text += std::string(std::size_t(depth), '[') + std::string(std::size_t(depth), ']');
  return text + "}], " + triangle_buffers + "}";
}

std::string repeat(const std::string& piece, int times) {
  std::string text;
  for (int k = 0; k < times; ++k) text += piece;
  return text;
}

bool write(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.close();
  if (!out) std::fprintf(stderr, "write_nesting_seeds: cannot write %s\n", path.c_str());
  return bool(out);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: write_nesting_seeds GLTF_SEED_FOLDER MANIFEST_SEED_FOLDER\n");
    return 2;
  }
  const std::string gltf = argv[1], manifest = argv[2];
  const bool ok =
      write(gltf + "/deep_node_chain.gltf", node_chain(20000)) &&
      write(gltf + "/deep_extras.gltf", deep_extras(100000)) &&
      write(manifest + "/deep_array.json", "{\"name\": " + std::string(100000, '[') + "}") &&
      write(manifest + "/deep_camera.json",
            R"({"name": "deep", "camera": )" + repeat("{\"a\": ", 50000) + "1}");
  return ok ? 0 : 1;
}
