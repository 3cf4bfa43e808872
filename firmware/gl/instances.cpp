#include "gl/instances.h"

#include <cstdint>

namespace candela {

void vec4_attribute(GLuint location, int vec4_index, int stride_vec4, bool instanced) {
  glEnableVertexAttribArray(location);
  glVertexAttribPointer(
      location, 4, GL_FLOAT, GL_FALSE, stride_vec4 * 4 * static_cast<GLsizei>(sizeof(float)),
      reinterpret_cast<const void*>(static_cast<uintptr_t>(vec4_index) * 4 * sizeof(float)));
  if (instanced) glVertexAttribDivisor(location, 1);
}

InstanceBuffer::InstanceBuffer(int vec4s, size_t capacity)
    : buffer_(make_buffer()),
      data_(capacity * static_cast<size_t>(vec4s) * 4, 0.0f),
      vec4s_(vec4s) {
  glBindBuffer(GL_ARRAY_BUFFER, buffer_.get());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data_.size() * sizeof(float)), nullptr,
               GL_STREAM_DRAW);
}

void InstanceBuffer::bind_attributes(GLuint first_location) const {
  glBindBuffer(GL_ARRAY_BUFFER, buffer_.get());
  for (int k = 0; k < vec4s_; ++k)
    vec4_attribute(first_location + static_cast<GLuint>(k), k, vec4s_, true);
}

void InstanceBuffer::upload() const {
  glBindBuffer(GL_ARRAY_BUFFER, buffer_.get());
  glBufferSubData(GL_ARRAY_BUFFER, 0,
                  static_cast<GLsizeiptr>(static_cast<size_t>(count_) * vec4s_ * 4 * sizeof(float)),
                  data_.data());
}

Billboards::Billboards(const char* vert, const char* frag, int vec4s, size_t max_instances)
    : prog_(Program::from_library(vert, frag)),
      vp_(prog_.uniform("u_view_projection")),
      right_(prog_.uniform("u_right")),
      up_(prog_.uniform("u_up")),
      vao_(make_vertex_array()),
      instances_(vec4s, max_instances) {
  glBindVertexArray(vao_.get());
  instances_.bind_attributes(0);
  glBindVertexArray(0);
}

void Billboards::draw(const Mat4& view_projection, const Vec3& right, const Vec3& up) const {
  prog_.use();
  glUniformMatrix4fv(vp_, 1, GL_FALSE, view_projection.m);
  glUniform3f(right_, right.x, right.y, right.z);
  glUniform3f(up_, up.x, up.y, up.z);
  glBindVertexArray(vao_.get());
  glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, instances_.count());
}

InstancedMesh::InstancedMesh(std::span<const float> vertices, std::initializer_list<int> layout,
                             std::span<const unsigned short> indices, int instance_vec4s,
                             size_t max_instances)
    : vao_(make_vertex_array()),
      vertices_(make_buffer()),
      indices_(make_buffer()),
      index_count_(static_cast<GLsizei>(indices.size())) {
  glBindVertexArray(vao_.get());
  glBindBuffer(GL_ARRAY_BUFFER, vertices_.get());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size_bytes()), vertices.data(),
               GL_STATIC_DRAW);
  int stride = 0;
  for (int n : layout) stride += n;
  GLuint location = 0;
  int offset = 0;
  for (int n : layout) {
    glEnableVertexAttribArray(location);
    glVertexAttribPointer(
        location, n, GL_FLOAT, GL_FALSE, stride * static_cast<GLsizei>(sizeof(float)),
        reinterpret_cast<const void*>(static_cast<uintptr_t>(offset) * sizeof(float)));
    ++location;
    offset += n;
  }
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices_.get());
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(indices.size_bytes()),
               indices.data(), GL_STATIC_DRAW);
  instances_ = InstanceBuffer(instance_vec4s, max_instances);
  instances_.bind_attributes(location);
  glBindVertexArray(0);
}

void InstancedMesh::draw() const {
  glBindVertexArray(vao_.get());
  glDrawElementsInstanced(GL_TRIANGLES, index_count_, GL_UNSIGNED_SHORT, nullptr,
                          instances_.count());
}

}  // namespace candela
