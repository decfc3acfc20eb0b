#pragma once
// glTF accessors read with every bound checked (tinygltf does not validate accessor indices,
// offsets or counts against their buffers): indices as uint32, positions as float.
// tinygltf is the Debian shared library: TINYGLTF_IMPLEMENTATION must not be defined anywhere.
#include <tiny_gltf.h>

#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "shadowcts/errors.h"

namespace shadowcts {

inline std::string accessor_element(const std::string& user, int accessor_index) {
  return user + " (accessor " + std::to_string(accessor_index) + ")";
}

class ModelReader {
 public:
  // Elements of an accessor without a bufferView (2^24: 192 MiB of float positions).
  static constexpr std::size_t max_elements_without_view = std::size_t{1} << 24;

  ModelReader(const std::string& path, const tinygltf::Model& model) : path_(path), model_(model) {}

  // Reads the accessor as `components` values per element of component type `component_type`,
  // converted to uint32 (indices) or float (positions). `user` names the referencing element.
  template <typename Value>
  std::vector<Value> read(int accessor_index, const std::string& user, int expected_type,
                          const std::vector<int>& allowed_component_types) {
    const std::string element = accessor_element(user, accessor_index);
    if (accessor_index < 0 || static_cast<std::size_t>(accessor_index) >= model_.accessors.size()) {
      throw InputError(path_, element,
                       "accessor index out of range (" + std::to_string(model_.accessors.size()) +
                           " accessors)");
    }
    const tinygltf::Accessor& accessor = model_.accessors[static_cast<std::size_t>(accessor_index)];
    const std::string accessor_path = "accessors[" + std::to_string(accessor_index) + "]";
    if (accessor.type != expected_type) {
      throw InputError(
          path_, element,
          "type must be " + type_name(expected_type) + ", is " + type_name(accessor.type));
    }
    if (std::find(allowed_component_types.begin(), allowed_component_types.end(),
                  accessor.componentType) == allowed_component_types.end()) {
      std::string allowed;
      for (const int t : allowed_component_types) {
        allowed += (allowed.empty() ? "" : " or ") + component_type_name(t);
      }
      throw InputError(path_, element,
                       "componentType must be " + allowed + ", is " +
                           component_type_name(accessor.componentType));
    }
    const std::size_t components = static_cast<std::size_t>(
        tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(accessor.type)));
    const std::size_t component_size = static_cast<std::size_t>(
        tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(accessor.componentType)));
    const std::size_t element_size = components * component_size;

    // Every range is checked before anything is allocated: `count` is only a claim of the file
    // (2^32 - 1 indices in a 598-byte file took 16.9 GB before the bounds check).
    const unsigned char* data = nullptr;
    std::size_t stride = 0;
    if (accessor.bufferView >= 0) {
      std::tie(data, stride) = view_range(accessor.bufferView, accessor.byteOffset, accessor.count,
                                          element_size, element, accessor_path);
    } else if (!accessor.sparse.isSparse) {
      throw InputError(path_, element, "has neither a bufferView nor sparse values");
    } else if (accessor.count > max_elements_without_view) {
      // Zeros but for the sparse values: no byte of the file backs them, so they are capped.
      throw InputError(path_, element,
                       "count " + std::to_string(accessor.count) +
                           " without a bufferView (zeros but for the sparse values) exceeds " +
                           std::to_string(max_elements_without_view) +
                           " elements; give the base values in a bufferView");
    }

    const unsigned char* index_data = nullptr;
    const unsigned char* value_data = nullptr;
    std::size_t index_size = 0, sparse_count = 0;
    int index_type = 0;
    const std::string sparse_element = element + " sparse";
    if (accessor.sparse.isSparse) {
      // Sparse substitution: count (index, value) pairs replace elements of the base data.
      if (accessor.sparse.count <= 0 ||
          static_cast<std::size_t>(accessor.sparse.count) > accessor.count) {
        throw InputError(path_, sparse_element,
                         "count " + std::to_string(accessor.sparse.count) +
                             " must be in [1, accessor count " + std::to_string(accessor.count) +
                             "]");
      }
      sparse_count = static_cast<std::size_t>(accessor.sparse.count);
      index_type = accessor.sparse.indices.componentType;
      if (index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
          index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
          index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
        throw InputError(path_, sparse_element + ".indices",
                         "componentType must be unsigned, is " + component_type_name(index_type));
      }
      index_size = static_cast<std::size_t>(
          tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(index_type)));
      index_data =
          view_range(accessor.sparse.indices.bufferView,
                     static_cast<std::size_t>(std::max(0, accessor.sparse.indices.byteOffset)),
                     sparse_count, index_size, sparse_element + ".indices",
                     accessor_path + ".sparse.indices")
              .first;
      value_data =
          view_range(accessor.sparse.values.bufferView,
                     static_cast<std::size_t>(std::max(0, accessor.sparse.values.byteOffset)),
                     sparse_count, element_size, sparse_element + ".values",
                     accessor_path + ".sparse.values")
              .first;
    }

    std::vector<Value> values(accessor.count * components, Value(0));
    if (data) {
      for (std::size_t i = 0; i < accessor.count; ++i) {
        for (std::size_t c = 0; c < components; ++c) {
          values[i * components + c] =
              decode<Value>(data + i * stride + c * component_size, accessor.componentType);
        }
      }
    }
    for (std::size_t k = 0; k < sparse_count; ++k) {
      const std::uint32_t target = decode<std::uint32_t>(index_data + k * index_size, index_type);
      if (target >= accessor.count) {
        throw InputError(path_, sparse_element + ".indices",
                         "index " + std::to_string(target) + " at position " + std::to_string(k) +
                             " is out of range for " + std::to_string(accessor.count) +
                             " elements");
      }
      for (std::size_t c = 0; c < components; ++c) {
        values[target * components + c] = decode<Value>(
            value_data + k * element_size + c * component_size, accessor.componentType);
      }
    }
    return values;
  }

 private:
  // Start of the data and the stride of `count` elements of `element_size` bytes at `offset`
  // in buffer view `view_index`, after checking that all of them lie inside the view and the
  // view inside its buffer.
  std::pair<const unsigned char*, std::size_t> view_range(int view_index, std::size_t offset,
                                                          std::size_t count,
                                                          std::size_t element_size,
                                                          const std::string& element,
                                                          const std::string& accessor_path) {
    if (view_index < 0 || static_cast<std::size_t>(view_index) >= model_.bufferViews.size()) {
      throw InputError(path_, element,
                       accessor_path + ".bufferView " + std::to_string(view_index) +
                           " is out of range (" + std::to_string(model_.bufferViews.size()) +
                           " buffer views)");
    }
    const tinygltf::BufferView& view = model_.bufferViews[static_cast<std::size_t>(view_index)];
    const std::string view_path = "bufferViews[" + std::to_string(view_index) + "]";
    if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model_.buffers.size()) {
      throw InputError(path_, view_path,
                       "buffer " + std::to_string(view.buffer) + " is out of range (" +
                           std::to_string(model_.buffers.size()) + " buffers)");
    }
    const std::size_t buffer_size =
        model_.buffers[static_cast<std::size_t>(view.buffer)].data.size();
    if (view.byteOffset > buffer_size || view.byteLength > buffer_size - view.byteOffset) {
      throw InputError(path_, view_path,
                       "byteOffset " + std::to_string(view.byteOffset) + " + byteLength " +
                           std::to_string(view.byteLength) + " exceeds buffer " +
                           std::to_string(view.buffer) + " (" + std::to_string(buffer_size) +
                           " bytes)");
    }
    const std::size_t stride = view.byteStride == 0 ? element_size : view.byteStride;
    if (stride < element_size) {
      throw InputError(path_, view_path,
                       "byteStride " + std::to_string(view.byteStride) +
                           " is smaller than the element size " + std::to_string(element_size) +
                           " of " + element);
    }
    // The last element ends at offset + (count - 1) * stride + element_size (glTF 2.0, 3.6.2.4);
    // computed without overflow.
    const bool fits =
        count == 0 ||
        (offset <= view.byteLength && count - 1 <= (view.byteLength - offset) / stride &&
         element_size <= view.byteLength - offset - (count - 1) * stride);
    if (!fits) {
      throw InputError(path_, element,
                       "byteOffset " + std::to_string(offset) + " + " + std::to_string(count) +
                           " elements of " + std::to_string(element_size) + " bytes (stride " +
                           std::to_string(stride) + ") exceed " + view_path + " (" +
                           std::to_string(view.byteLength) + " bytes)");
    }
    const auto& data = model_.buffers[static_cast<std::size_t>(view.buffer)].data;
    return {data.data() + view.byteOffset + offset, stride};
  }

  template <typename Value>
  static Value decode(const unsigned char* p, int component_type) {
    switch (component_type) {
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return static_cast<Value>(*p);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        std::uint16_t v;
        std::memcpy(&v, p, sizeof v);
        return static_cast<Value>(v);
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        std::uint32_t v;
        std::memcpy(&v, p, sizeof v);
        return static_cast<Value>(v);
      }
      case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        float v;
        std::memcpy(&v, p, sizeof v);
        return static_cast<Value>(v);
      }
      default:
        return Value(0);  // unreachable: component types are checked before decoding
    }
  }

  static std::string type_name(int type) {
    switch (type) {
      case TINYGLTF_TYPE_SCALAR:
        return "SCALAR";
      case TINYGLTF_TYPE_VEC2:
        return "VEC2";
      case TINYGLTF_TYPE_VEC3:
        return "VEC3";
      case TINYGLTF_TYPE_VEC4:
        return "VEC4";
      case TINYGLTF_TYPE_MAT2:
        return "MAT2";
      case TINYGLTF_TYPE_MAT3:
        return "MAT3";
      case TINYGLTF_TYPE_MAT4:
        return "MAT4";
      default:
        return "unknown (" + std::to_string(type) + ")";
    }
  }

  static std::string component_type_name(int component_type) {
    switch (component_type) {
      case TINYGLTF_COMPONENT_TYPE_BYTE:
        return "BYTE";
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return "UNSIGNED_BYTE";
      case TINYGLTF_COMPONENT_TYPE_SHORT:
        return "SHORT";
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return "UNSIGNED_SHORT";
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        return "UNSIGNED_INT";
      case TINYGLTF_COMPONENT_TYPE_FLOAT:
        return "FLOAT";
      default:
        return "unknown (" + std::to_string(component_type) + ")";
    }
  }

  const std::string& path_;
  const tinygltf::Model& model_;
};

}  // namespace shadowcts
