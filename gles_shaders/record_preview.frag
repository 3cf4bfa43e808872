#version 300 es
// candela-record's live preview: the newest recorded frame, gray or RGB.
precision mediump float;

uniform sampler2D u_frame;
uniform int u_gray;  // 1: the texture holds luma in .r
in vec2 v_uv;
out vec4 o_color;

void main() {
  // Frames are uploaded top row first; v_uv.y grows upwards.
  vec3 c = texture(u_frame, vec2(v_uv.x, 1.0 - v_uv.y)).rgb;
  o_color = vec4(u_gray == 1 ? c.rrr : c, 1.0);
}
