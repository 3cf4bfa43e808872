#version 300 es
// A flat quad on the floor (gl_VertexID 0..3, a strip): the eigen-flames' and the hearth's ember beds.
precision highp float;
uniform mat4 u_view_projection;
uniform vec3 u_centre;
uniform vec2 u_half;  // half width (x), half depth (z)
out vec2 v_uv;
void main() {
  vec2 c = vec2(float(gl_VertexID & 1), float((gl_VertexID >> 1) & 1)) * 2.0 - 1.0;
  v_uv = c;
  gl_Position = u_view_projection * vec4(u_centre + vec3(c.x * u_half.x, 0.0, c.y * u_half.y), 1.0);
}
