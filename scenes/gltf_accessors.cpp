// Reading glTF accessors: typed views into the binary buffers (glTF spec Sec. 3.6 "Binary Data Storage").
//
// An accessor says: `count` elements of `type` (SCALAR, VEC2, ...) made of `componentType` components,
// starting `byteOffset` bytes into a bufferView, one element every `byteStride` bytes (tightly packed when
// the stride is 0). A bufferView is a byte range of a buffer. Every one of those numbers comes from the
// file, so each is checked before a single byte is read: a bad file gives an error, never a wild read.
#include "scenes/gltf_parts.h"

#include "core/error.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace rtdr::gltf {

void Source::fail(const std::string& problem) const { throw Error(path + ": " + problem); }

std::string label(const std::string& name, size_t index) {
  std::string text = name.empty() ? std::string("#") : std::string("'");
  text += name.empty() ? std::to_string(index) : name + "'";
  return text;
}

namespace {

// Where an accessor's elements lie, after every range check.
struct ElementBytes {
  const unsigned char* first = nullptr;  // the first component of the first element
  size_t stride = 0;                     // bytes from one element to the next
  size_t count = 0;                      // elements
  int component_type = 0;                // TINYGLTF_COMPONENT_TYPE_*
  int component_size = 0;                // bytes per component
  bool normalized = false;
};

const char* type_name(int components) {
  switch (components) {
    case 1: return "SCALAR";
    case 2: return "VEC2";
    case 3: return "VEC3";
    case 4: return "VEC4";
    default: return "a matrix or unknown type";
  }
}

// The component types glTF 2.0 allows in accessors (spec Sec. 3.6.2.2); tinygltf also knows INT and DOUBLE.
bool is_gltf_component_type(int t) {
  return t == TINYGLTF_COMPONENT_TYPE_BYTE || t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
         t == TINYGLTF_COMPONENT_TYPE_SHORT || t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
         t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT || t == TINYGLTF_COMPONENT_TYPE_FLOAT;
}

ElementBytes locate(const Source& src, int index, int components, const std::string& what) {
  const tinygltf::Model& m = src.model;
  if (index < 0 || size_t(index) >= m.accessors.size())
    src.fail(what + " refers to accessor " + std::to_string(index) + ", out of range (the file has " +
             std::to_string(m.accessors.size()) + ")");
  const tinygltf::Accessor& a = m.accessors[size_t(index)];
  const std::string name = what + " (accessor " + std::to_string(index) + ")";

  // The element's layout.
  if (a.sparse.isSparse) src.fail(name + " is sparse; sparse accessors are not supported");
  if (tinygltf::GetNumComponentsInType(uint32_t(a.type)) != components)
    src.fail(name + " is not " + type_name(components));
  if (!is_gltf_component_type(a.componentType))
    src.fail(name + " has unsupported componentType " + std::to_string(a.componentType));
  if (a.count == 0) src.fail(name + " has count 0 (glTF requires at least 1)");
  const size_t component_size = size_t(tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType)));
  const size_t element_size = component_size * size_t(components);

  // The bufferView must lie inside its buffer.
  if (a.bufferView < 0 || size_t(a.bufferView) >= m.bufferViews.size())
    src.fail(name + " refers to bufferView " + std::to_string(a.bufferView) + ", out of range");
  const tinygltf::BufferView& view = m.bufferViews[size_t(a.bufferView)];
  if (view.buffer < 0 || size_t(view.buffer) >= m.buffers.size())
    src.fail(name + ": bufferView " + std::to_string(a.bufferView) + " refers to buffer " +
             std::to_string(view.buffer) + ", out of range");
  const std::vector<unsigned char>& buffer = m.buffers[size_t(view.buffer)].data;
  if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset)
    src.fail(name + ": bufferView " + std::to_string(a.bufferView) + " (" + std::to_string(view.byteLength) +
             " bytes at offset " + std::to_string(view.byteOffset) + ") is out of range of buffer " +
             std::to_string(view.buffer) + " (" + std::to_string(buffer.size()) + " bytes)");

  // Every element must lie inside the bufferView: the last one ends at
  // byteOffset + (count - 1) * stride + element_size, compared below without overflowing.
  const size_t stride = view.byteStride == 0 ? element_size : view.byteStride;
  if (stride < element_size)
    src.fail(name + ": byteStride " + std::to_string(stride) + " is smaller than an element (" +
             std::to_string(element_size) + " bytes)");
  const bool fits = a.byteOffset <= view.byteLength && element_size <= view.byteLength - a.byteOffset &&
                    a.count - 1 <= (view.byteLength - a.byteOffset - element_size) / stride;
  if (!fits)
    src.fail(name + " is out of range: " + std::to_string(a.count) + " elements of " + std::to_string(element_size) +
             " bytes do not fit in bufferView " + std::to_string(a.bufferView) + " (" +
             std::to_string(view.byteLength) + " bytes)");

  ElementBytes e;
  e.first = buffer.data() + view.byteOffset + a.byteOffset;
  e.stride = stride;
  e.count = a.count;
  e.component_type = a.componentType;
  e.component_size = int(component_size);
  e.normalized = a.normalized;
  return e;
}

// One component as a float. Normalised integers map to [0, 1] or [-1, 1] by the equations of glTF spec
// Sec. 3.11 (e.g. f = max(c / 127, -1) for signed bytes); other integers convert as they are.
float component_as_float(const unsigned char* p, int component_type, bool normalized) {
  auto load = [p](auto value) {  // memcpy: components need not be aligned in a strided view
    std::memcpy(&value, p, sizeof value);
    return value;
  };
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return load(float{});
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const float c = float(load(int8_t{}));
      return normalized ? std::max(c / 127.0f, -1.0f) : c;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      const float c = float(load(uint8_t{}));
      return normalized ? c / 255.0f : c;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      const float c = float(load(int16_t{}));
      return normalized ? std::max(c / 32767.0f, -1.0f) : c;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      const float c = float(load(uint16_t{}));
      return normalized ? c / 65535.0f : c;
    }
    default: {  // UNSIGNED_INT, the only other type locate() lets through
      const double c = double(load(uint32_t{}));
      return float(normalized ? c / 4294967295.0 : c);
    }
  }
}

}  // namespace

std::vector<float> read_floats(const Source& src, int accessor, int components, const std::string& what) {
  const ElementBytes e = locate(src, accessor, components, what);
  std::vector<float> values;
  values.reserve(e.count * size_t(components));
  for (size_t i = 0; i < e.count; ++i) {
    const unsigned char* element = e.first + i * e.stride;
    for (int c = 0; c < components; ++c) {
      const float v =
          component_as_float(element + size_t(c) * size_t(e.component_size), e.component_type, e.normalized);
      if (!std::isfinite(v))
        src.fail(what + " (accessor " + std::to_string(accessor) + ") element " + std::to_string(i) +
                 " is not a finite number");
      values.push_back(v);
    }
  }
  return values;
}

std::vector<uint32_t> read_indices(const Source& src, int accessor, const std::string& what) {
  const ElementBytes e = locate(src, accessor, 1, what);
  // glTF spec Sec. 3.7.2.1: indices are UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT.
  const int t = e.component_type;
  if (t != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && t != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      t != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    src.fail(what + " (accessor " + std::to_string(accessor) + ") has componentType " + std::to_string(t) +
             "; indices must be unsigned bytes, shorts or ints");
  std::vector<uint32_t> indices(e.count);
  for (size_t i = 0; i < e.count; ++i) {
    const unsigned char* p = e.first + i * e.stride;
    if (t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) {
      indices[i] = *p;
    } else if (t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
      uint16_t v;
      std::memcpy(&v, p, sizeof v);
      indices[i] = v;
    } else {
      std::memcpy(&indices[i], p, sizeof(uint32_t));
    }
  }
  return indices;
}

void check_keys(const Source& src, const std::vector<float>& times, size_t value_count, const std::string& what) {
  if (times.empty()) src.fail(what + " has no keys");
  if (value_count != times.size())
    src.fail(what + " has " + std::to_string(times.size()) + " key times but " + std::to_string(value_count) +
             " values");
  for (size_t k = 1; k < times.size(); ++k)
    if (!(times[k] > times[k - 1]))
      src.fail(what + " key times are not strictly increasing (key " + std::to_string(k) + ": " +
               std::to_string(times[k]) + " after " + std::to_string(times[k - 1]) + ")");
}

}  // namespace rtdr::gltf
