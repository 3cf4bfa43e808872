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
  // The quad only as big as the glow can still show: past the radius where
  // its brightest channel falls under 0.4/255 (candle_glow.frag's outer bell
  // (1 - r^2)^4), an 8-bit framebuffer adds nothing, and the pixels there
  // would be shaded for naught (a hundred overlapping glows are most of what
  // a candle scene costs on a software renderer). The inner part ends at r^2 = 1/6.
  float peak = max(max(a_color.r, a_color.g), a_color.b) * a_color.a;
  float cut = peak > 0.0 ? sqrt(clamp(1.0 - sqrt(sqrt(0.4 / 255.0 / peak)), 1.0 / 6.0, 1.0)) : 0.0;
  vec2 corner = vec2(float(gl_VertexID & 1) * 2.0 - 1.0, float((gl_VertexID >> 1) & 1) * 2.0 - 1.0) * cut;
  vec3 world = a_center.xyz + (u_right * corner.x + u_up * corner.y) * (0.5 * a_center.w);
  gl_Position = u_view_projection * vec4(world, 1.0);
  v_p = corner;
  v_color = a_color;
}
