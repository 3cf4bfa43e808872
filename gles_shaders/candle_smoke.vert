#version 300 es
// A short smoke wisp rising from a wick that just went out.
precision highp float;

layout(location = 0) in vec4 a_origin;  // wick tip xyz, age 0..1
layout(location = 1) in vec4 a_shape;   // scale, phase, -, -

uniform mat4 u_view_projection;
uniform vec3 u_right;
uniform vec3 u_up;

out vec2 v_p;
out float v_age;
out float v_phase;

void main() {
  vec2 corner = vec2(float(gl_VertexID & 1) * 2.0 - 1.0, float((gl_VertexID >> 1) & 1));
  float s = a_shape.x;
  float rise = 0.03 * a_origin.w * s;
  vec3 world = a_origin.xyz + u_right * (corner.x * 0.025 * s) + u_up * (corner.y * 0.13 * s + rise);
  gl_Position = u_view_projection * vec4(world, 1.0);
  v_p = corner;
  v_age = a_origin.w;
  v_phase = a_shape.y;
}
