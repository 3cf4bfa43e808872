#version 300 es
// The light a flame casts into the air: a camera-facing quad per candle
// (corners from gl_VertexID), instanced.
precision highp float;

layout(location = 0) in vec4 a_center;  // world xyz, diameter (m)
layout(location = 1) in vec4 a_color;   // rgb, strength

uniform mat4 u_view_projection;
uniform vec3 u_right;
uniform vec3 u_up;

out vec2 v_p;
out vec4 v_color;

void main() {
  vec2 corner = vec2(float(gl_VertexID & 1) * 2.0 - 1.0, float((gl_VertexID >> 1) & 1) * 2.0 - 1.0);
  vec3 world = a_center.xyz + (u_right * corner.x + u_up * corner.y) * (0.5 * a_center.w);
  gl_Position = u_view_projection * vec4(world, 1.0);
  v_p = corner;
  v_color = a_color;
}
