// Instanced drawing: per-instance records staged on the CPU into storage
// allocated once, uploaded in one call, read by vertex attributes with a
// divisor of 1; Billboards, camera-facing quads drawn that way; and
// InstancedMesh, a static indexed mesh drawn that way.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <span>
#include <vector>

#include "gl/math.h"
#include "gl/program.h"
#include "gl/texture.h"

namespace candela {

// Attribute `location` reads vec4 number `vec4_index` of records `stride_vec4`
// vec4s long from the bound GL_ARRAY_BUFFER; per instance if `instanced`.
void vec4_attribute(GLuint location, int vec4_index, int stride_vec4, bool instanced);

// Records of `vec4s` vec4s, at most `capacity` of them. Fill them in an
// element's prepare() (scene/element.h) and upload(); draw with count().
// Nothing is allocated after construction.
class InstanceBuffer {
 public:
  InstanceBuffer() = default;
  InstanceBuffer(int vec4s, size_t capacity);

  // With the vertex array bound: attributes first_location... read one
  // record per instance.
  void bind_attributes(GLuint first_location) const;
  void clear() { count_ = 0; }
  // The next record's vec4s * 4 floats.
  float* add() { return record(static_cast<size_t>(count_++)); }
  // Record i, for filling out of order (then set_count()).
  float* record(size_t i) { return &data_[i * static_cast<size_t>(vec4s_) * 4]; }
  void set_count(int n) { count_ = n; }
  int count() const { return count_; }
  // The first count() records to the GPU (leaves the buffer bound).
  void upload() const;

 private:
  Buffer buffer_;
  std::vector<float> data_;
  int vec4s_ = 0, count_ = 0;
};

// Camera-facing quads, one per instance, corners from gl_VertexID: the
// shaders take u_view_projection, u_right and u_up, and the instance's
// vec4s as attributes 0...
class Billboards {
 public:
  Billboards() = default;
  Billboards(const char* vert, const char* frag, int vec4s, size_t max_instances);
  InstanceBuffer& instances() { return instances_; }
  int count() const { return instances_.count(); }
  // Draws the uploaded instances with the caller's blending and depth state.
  void draw(const Mat4& view_projection, const Vec3& right, const Vec3& up) const;

 private:
  Program prog_;
  GLint vp_ = -1, right_ = -1, up_ = -1;
  VertexArray vao_;
  InstanceBuffer instances_;
};

// A static indexed mesh, uploaded once, drawn once per instance record:
// per vertex the attributes `layout` says (floats each, interleaved,
// locations 0...), then the instance's vec4s at the locations after them.
// Draw with the caller's program and state.
class InstancedMesh {
 public:
  InstancedMesh() = default;
  InstancedMesh(std::span<const float> vertices, std::initializer_list<int> layout,
                std::span<const unsigned short> indices, int instance_vec4s, size_t max_instances);
  InstanceBuffer& instances() { return instances_; }
  int count() const { return instances_.count(); }
  // Draws the uploaded instances as indexed triangles.
  void draw() const;

 private:
  VertexArray vao_;
  Buffer vertices_, indices_;
  GLsizei index_count_ = 0;
  InstanceBuffer instances_;
};

}  // namespace candela
