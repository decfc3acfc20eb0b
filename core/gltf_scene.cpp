#include "gltf_scene.h"

#include <cmath>
#include <cstdio>
#include <functional>
#include <span>
#include <tuple>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>

#include "gltf_accessors.h"
#include "shadowcts/closed_surface.h"
#include "shadowcts/errors.h"

namespace shadowcts {
namespace {

std::string coordinates(const glm::dvec3& p) {
  char text[96];
  std::snprintf(text, sizeof text, "(%.9g, %.9g, %.9g)", p.x, p.y, p.z);
  return text;
}

bool all_finite(const glm::dmat4& m) {
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) {
      if (!std::isfinite(m[c][r])) return false;
    }
  }
  return true;
}

class SceneBuilder {
 public:
  SceneBuilder(const std::string& path, const tinygltf::Model& model, LoadedScene& scene)
      : path_(path), model_(model), scene_(scene), reader_(path, model) {}

  void add_root(int node_index) { visit_tree(node_index); }

 private:
  // Local transform of a node: its matrix, or T * R * S (glTF 2.0, 3.5.3).
  glm::dmat4 local_transform(const tinygltf::Node& node, const std::string& node_path) {
    auto require_finite = [&](const std::vector<double>& values, const char* property) {
      for (std::size_t i = 0; i < values.size(); ++i) {
        if (!std::isfinite(values[i])) {
          throw InputError(path_, node_path + "." + property + "[" + std::to_string(i) + "]",
                           "is not finite");
        }
      }
    };
    if (!node.matrix.empty()) {
      if (node.matrix.size() != 16) {
        throw InputError(path_, node_path + ".matrix", "must have 16 elements");
      }
      require_finite(node.matrix, "matrix");
      if (!node.translation.empty() || !node.rotation.empty() || !node.scale.empty()) {
        scene_.warnings.push_back(path_ + ": " + node_path +
                                  ": has both matrix and TRS properties; the matrix is used");
      }
      glm::dmat4 m(1.0);
      for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) m[c][r] = node.matrix[static_cast<std::size_t>(c * 4 + r)];
      }
      if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0) {
        throw InputError(path_, node_path + ".matrix", "is not affine (last row must be 0 0 0 1)");
      }
      return m;
    }
    glm::dvec3 translation(0.0), scale(1.0);
    glm::dquat rotation(1.0, 0.0, 0.0, 0.0);  // w, x, y, z
    if (!node.translation.empty()) {
      if (node.translation.size() != 3) {
        throw InputError(path_, node_path + ".translation", "must have 3 elements");
      }
      require_finite(node.translation, "translation");
      translation = glm::dvec3(node.translation[0], node.translation[1], node.translation[2]);
    }
    if (!node.rotation.empty()) {
      if (node.rotation.size() != 4) {
        throw InputError(path_, node_path + ".rotation", "must have 4 elements");
      }
      require_finite(node.rotation, "rotation");
      // glTF stores x, y, z, w.
      rotation = glm::dquat(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
      const double length = glm::length(rotation);
      if (length == 0.0) throw InputError(path_, node_path + ".rotation", "is a zero quaternion");
      rotation = rotation / length;
    }
    if (!node.scale.empty()) {
      if (node.scale.size() != 3)
        throw InputError(path_, node_path + ".scale", "must have 3 elements");
      require_finite(node.scale, "scale");
      scale = glm::dvec3(node.scale[0], node.scale[1], node.scale[2]);
    }
    glm::dmat4 m = glm::mat4_cast(rotation);
    m[0] *= scale.x;
    m[1] *= scale.y;
    m[2] *= scale.z;
    m[3] = glm::dvec4(translation, 1.0);
    return m;
  }

  // Depth-first in the file's child order, with an explicit stack: a chain of 20,000 nodes
  // overflowed the call stack when this recursed (and copied the ancestor list per level, 426 MB
  // at depth 10,000). Memory is linear in the node count: one frame per level of the current
  // path and one on-path flag per node for the cycle check.
  void visit_tree(int root) {
    if (on_path_.empty()) {
      on_path_.assign(model_.nodes.size(), 0);
      visited_.assign(model_.nodes.size(), 0);
    }
    struct Frame {
      int node;
      glm::dmat4 world;
      int singular;  // the nearest node at or above this one with a singular transform, or -1
      std::size_t next_child;
    };
    std::vector<Frame> path;
    auto enter = [&](int node_index, const glm::dmat4& parent, int singular) {
      const glm::dmat4 world = place_node(node_index, parent, singular);
      on_path_[static_cast<std::size_t>(node_index)] = 1;
      path.push_back({node_index, world, singular, 0});
    };
    enter(root, glm::dmat4(1.0), -1);
    while (!path.empty()) {
      Frame& frame = path.back();
      const auto& children = model_.nodes[static_cast<std::size_t>(frame.node)].children;
      if (frame.next_child == children.size()) {
        on_path_[static_cast<std::size_t>(frame.node)] = 0;
        path.pop_back();
        continue;
      }
      const int child = children[frame.next_child++];
      const glm::dmat4 world = frame.world;  // `frame` dies when enter() grows `path`
      enter(child, world, frame.singular);
    }
  }

  // Checks one node reached below `parent` and adds its mesh and light; returns its world
  // transform. `singular` (in/out) is the nearest ancestor, or this node, whose linear part is
  // singular: meshes and lights below it are an error, empty subtrees are harmless.
  glm::dmat4 place_node(int node_index, const glm::dmat4& parent, int& singular) {
    const std::string node_path = "nodes[" + std::to_string(node_index) + "]";
    if (node_index < 0 || static_cast<std::size_t>(node_index) >= model_.nodes.size()) {
      throw InputError(
          path_, node_path,
          "node index out of range (" + std::to_string(model_.nodes.size()) + " nodes)");
    }
    const auto index = static_cast<std::size_t>(node_index);
    if (on_path_[index]) {
      throw InputError(path_, node_path, "is its own ancestor (cycle in the node hierarchy)");
    }
    if (visited_[index]) {
      throw InputError(path_, node_path,
                       "is reached twice (a node may have one parent and appear in one scene "
                       "only)");
    }
    visited_[index] = 1;
    const tinygltf::Node& node = model_.nodes[index];
    const glm::dmat4 local = local_transform(node, node_path);
    const double local_determinant = glm::determinant(glm::dmat3(local));
    if (singular < 0 && !(std::isfinite(local_determinant) && local_determinant != 0.0)) {
      singular = node_index;
    }
    const glm::dmat4 world = parent * local;
    if (!all_finite(world)) {
      throw InputError(path_, node_path, "world transform overflows (non-finite entries)");
    }
    const bool has_light = node.extensions.count("KHR_lights_punctual") > 0;
    if ((node.mesh >= 0 || has_light) && singular >= 0) {
      const tinygltf::Node& culprit = model_.nodes[static_cast<std::size_t>(singular)];
      throw InputError(
          path_,
          "nodes[" + std::to_string(singular) + "]" +
              (culprit.matrix.empty() ? ".scale" : ".matrix"),
          "singular transform (zero determinant) above the mesh or light of " + node_path);
    }
    if ((node.mesh >= 0 || has_light) && !(std::isfinite(glm::determinant(glm::dmat3(world))) &&
                                           glm::determinant(glm::dmat3(world)) != 0.0)) {
      throw InputError(path_, node_path, "world transform is singular (zero determinant)");
    }
    if (node.mesh >= 0) add_mesh_instance(node_index, node, world);
    if (has_light) add_light(node_index, node, world);
    return world;
  }

  void add_mesh_instance(int node_index, const tinygltf::Node& node, const glm::dmat4& world) {
    const std::string node_path = "nodes[" + std::to_string(node_index) + "]";
    if (static_cast<std::size_t>(node.mesh) >= model_.meshes.size()) {
      throw InputError(path_, node_path + ".mesh",
                       "mesh " + std::to_string(node.mesh) + " is out of range (" +
                           std::to_string(model_.meshes.size()) + " meshes)");
    }
    const tinygltf::Mesh& mesh = model_.meshes[static_cast<std::size_t>(node.mesh)];
    const std::string mesh_path = "meshes[" + std::to_string(node.mesh) + "]";
    if (node.skin >= 0) {
      scene_.warnings.push_back(path_ + ": " + node_path +
                                ": skinned mesh: the bind pose under the node transform is used");
    }
    // A negative determinant mirrors: glTF then defines front faces as clockwise, so the winding
    // is flipped to keep counter-clockwise front faces in world space.
    const bool mirrored = glm::determinant(glm::dmat3(world)) < 0.0;
    const auto mesh_id = static_cast<std::uint32_t>(scene_.meshes.size());
    const std::size_t first_triangle = scene_.triangles.size();

    for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
      const tinygltf::Primitive& primitive = mesh.primitives[p];
      const std::string primitive_path = mesh_path + ".primitives[" + std::to_string(p) + "]";
      if (primitive.mode != TINYGLTF_MODE_TRIANGLES) {
        scene_.warnings.push_back(path_ + ": " + primitive_path + ": mode " +
                                  std::to_string(primitive.mode) +
                                  " is not TRIANGLES (4); the primitive is skipped");
        continue;
      }
      if (!primitive.targets.empty() && (std::any_of(mesh.weights.begin(), mesh.weights.end(),
                                                     [](double w) { return w != 0.0; }) ||
                                         std::any_of(node.weights.begin(), node.weights.end(),
                                                     [](double w) { return w != 0.0; }))) {
        scene_.warnings.push_back(path_ + ": " + primitive_path +
                                  ": morph target weights are ignored; the base shape is used");
      }
      const auto position_it = primitive.attributes.find("POSITION");
      if (position_it == primitive.attributes.end()) {
        throw InputError(path_, primitive_path + ".attributes", "has no POSITION");
      }
      const std::string positions_user = primitive_path + ".attributes.POSITION";
      const std::vector<float> positions = reader_.read<float>(
          position_it->second, positions_user, TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT});
      const std::size_t vertex_count = positions.size() / 3;
      std::vector<glm::vec3> world_positions(vertex_count);
      // An identity transform keeps the file's floats, -0 included (1 * -0 + 0 is +0).
      const bool identity = world == glm::dmat4(1.0);
      for (std::size_t v = 0; v < vertex_count; ++v) {
        const glm::dvec3 local(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
        if (!std::isfinite(local.x) || !std::isfinite(local.y) || !std::isfinite(local.z)) {
          throw InputError(path_, accessor_element(positions_user, position_it->second),
                           "vertex " + std::to_string(v) + " is not finite");
        }
        const glm::dvec3 placed = identity ? local : glm::dvec3(world * glm::dvec4(local, 1.0));
        world_positions[v] = glm::vec3(placed);
        if (!std::isfinite(world_positions[v].x) || !std::isfinite(world_positions[v].y) ||
            !std::isfinite(world_positions[v].z)) {
          throw InputError(path_, accessor_element(positions_user, position_it->second),
                           "vertex " + std::to_string(v) + " leaves float range under " +
                               node_path + "'s world transform");
        }
        const double largest =
            std::max({std::fabs(placed.x), std::fabs(placed.y), std::fabs(placed.z)});
        if (largest > max_scene_coordinate) {
          throw InputError(path_, accessor_element(positions_user, position_it->second),
                           "vertex " + std::to_string(v) + " lies at " + coordinates(placed) +
                               " under " + node_path +
                               "'s world transform, beyond 1e30 (the largest coordinate a case "
                               "accepts)");
        }
      }

      std::vector<std::uint32_t> indices;
      const std::string indices_user = primitive_path + ".indices";
      if (primitive.indices >= 0) {
        indices = reader_.read<std::uint32_t>(
            primitive.indices, indices_user, TINYGLTF_TYPE_SCALAR,
            {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
             TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT});
        for (std::size_t i = 0; i < indices.size(); ++i) {
          if (indices[i] >= vertex_count) {
            throw InputError(path_, accessor_element(indices_user, primitive.indices),
                             "index " + std::to_string(indices[i]) + " at position " +
                                 std::to_string(i) + " is out of range for " +
                                 std::to_string(vertex_count) + " vertices");
          }
        }
        if (indices.size() % 3 != 0) {
          throw InputError(
              path_, accessor_element(indices_user, primitive.indices),
              "count " + std::to_string(indices.size()) + " is not a multiple of 3 (TRIANGLES)");
        }
      } else {
        if (vertex_count % 3 != 0) {
          throw InputError(path_, accessor_element(positions_user, position_it->second),
                           "count " + std::to_string(vertex_count) +
                               " is not a multiple of 3 (non-indexed TRIANGLES)");
        }
        indices.resize(vertex_count);
        for (std::size_t i = 0; i < vertex_count; ++i) indices[i] = static_cast<std::uint32_t>(i);
      }
      for (std::size_t i = 0; i + 2 < indices.size(); i += 3) {
        const glm::vec3& a = world_positions[indices[i]];
        const glm::vec3& b = world_positions[indices[i + 1]];
        const glm::vec3& c = world_positions[indices[i + 2]];
        scene_.triangles.push_back(mirrored ? Triangle{a, c, b, mesh_id}
                                            : Triangle{a, b, c, mesh_id});
      }
    }

    if (scene_.triangles.size() == first_triangle) {
      scene_.warnings.push_back(path_ + ": " + node_path + " (" + mesh_path +
                                "): no triangles; the mesh instance is skipped");
      return;
    }
    Mesh instance;
    instance.name = (node.name.empty() ? node_path : node.name) + "/" +
                    (mesh.name.empty() ? mesh_path : mesh.name);
    instance.closed =
        is_closed_surface(std::span<const Triangle>(scene_.triangles).subspan(first_triangle));
    scene_.meshes.push_back(std::move(instance));
  }

  void add_light(int node_index, const tinygltf::Node& node, const glm::dmat4& world) {
    const std::string node_path = "nodes[" + std::to_string(node_index) + "]";
    const tinygltf::Value& reference = node.extensions.at("KHR_lights_punctual");
    const std::string reference_path = node_path + ".extensions.KHR_lights_punctual.light";
    if (!reference.Has("light") || !reference.Get("light").IsNumber()) {
      throw InputError(path_, reference_path, "is missing");
    }
    const int light_index = reference.Get("light").GetNumberAsInt();
    if (light_index < 0 || static_cast<std::size_t>(light_index) >= model_.lights.size()) {
      throw InputError(path_, reference_path,
                       "light " + std::to_string(light_index) + " is out of range (" +
                           std::to_string(model_.lights.size()) + " lights)");
    }
    const tinygltf::Light& light = model_.lights[static_cast<std::size_t>(light_index)];
    const std::string light_path =
        "extensions.KHR_lights_punctual.lights[" + std::to_string(light_index) + "]";
    // Lights sit at the node's origin and shine along its local -Z (KHR_lights_punctual).
    const auto position = glm::vec3(glm::dvec3(world[3]));
    const glm::dvec3 axis = glm::dmat3(world) * glm::dvec3(0.0, 0.0, -1.0);
    const double axis_length = glm::length(axis);
    if (!std::isfinite(position.x) || !std::isfinite(position.y) || !std::isfinite(position.z)) {
      throw InputError(path_, node_path, "light position leaves float range");
    }
    if (!(axis_length > 0.0) || !std::isfinite(axis_length)) {
      throw InputError(path_, node_path, "light direction is degenerate under the node transform");
    }
    const auto emission = glm::vec3(axis / axis_length);
    const bool has_range = light.range > 0.0;
    if (light.range < 0.0 || !std::isfinite(light.range)) {
      throw InputError(path_, light_path + ".range",
                       "must be positive and finite, is " + std::to_string(light.range));
    }
    if (light.type == "directional") {
      ShadowLight shadow_light;
      shadow_light.kind = ShadowLightKind::directional;
      shadow_light.direction = -emission;  // from the scene towards the light
      scene_.shadow_lights.push_back(shadow_light);
    } else if (light.type == "point") {
      if (has_range) {
        RangedLight ranged;
        ranged.kind = RangedLightKind::sphere;
        ranged.centre = position;
        ranged.range = static_cast<float>(light.range);
        scene_.ranged_lights.push_back(ranged);
      } else {
        ShadowLight shadow_light;
        shadow_light.kind = ShadowLightKind::point;
        shadow_light.position = position;
        scene_.shadow_lights.push_back(shadow_light);
      }
    } else if (light.type == "spot") {
      const double outer = light.spot.outerConeAngle;
      if (!(outer > 0.0 && outer <= glm::pi<double>() / 2.0)) {
        throw InputError(path_, light_path + ".spot.outerConeAngle",
                         "must be in (0, pi/2], is " + std::to_string(outer));
      }
      if (!has_range) {
        // Light assignment needs a bounded volume and the shadow oracles have no cone: a spot
        // light without range has no meaning for either, so it is left out, loudly.
        scene_.warnings.push_back(path_ + ": " + light_path +
                                  ": spot light without range is skipped (light assignment "
                                  "needs a finite range)");
        return;
      }
      RangedLight ranged;
      ranged.kind = RangedLightKind::spot;
      ranged.centre = position;
      ranged.range = static_cast<float>(light.range);
      ranged.direction = emission;
      ranged.cone_half_angle = static_cast<float>(outer);
      scene_.ranged_lights.push_back(ranged);
    } else {
      throw InputError(path_, light_path + ".type",
                       "'" + light.type + "' is not point, directional or spot");
    }
  }

  const std::string& path_;
  const tinygltf::Model& model_;
  LoadedScene& scene_;
  ModelReader reader_;
  std::vector<char> on_path_, visited_;  // per node
};

}  // namespace

void add_gltf_scene(const std::string& path, const tinygltf::Model& model, LoadedScene& scene) {
  SceneBuilder builder(path, model, scene);
  if (!model.scenes.empty()) {
    int scene_index = model.defaultScene;
    if (scene_index < 0) scene_index = 0;
    if (static_cast<std::size_t>(scene_index) >= model.scenes.size()) {
      throw InputError(path, "scene",
                       std::to_string(scene_index) + " is out of range (" +
                           std::to_string(model.scenes.size()) + " scenes)");
    }
    for (const int root_node : model.scenes[static_cast<std::size_t>(scene_index)].nodes) {
      builder.add_root(root_node);
    }
  } else {
    // No scene at all: every node without a parent is a root (glTF leaves this to the loader).
    std::vector<bool> has_parent(model.nodes.size(), false);
    for (const auto& node : model.nodes) {
      for (const int child : node.children) {
        if (child >= 0 && static_cast<std::size_t>(child) < model.nodes.size()) {
          has_parent[static_cast<std::size_t>(child)] = true;
        }
      }
    }
    if (!model.nodes.empty()) {
      scene.warnings.push_back(path + ": scenes: none; every root node is loaded");
    }
    for (std::size_t n = 0; n < model.nodes.size(); ++n) {
      if (!has_parent[n]) builder.add_root(static_cast<int>(n));
    }
  }
}

}  // namespace shadowcts
