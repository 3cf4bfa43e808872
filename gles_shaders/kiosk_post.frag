#version 300 es
// The kiosk's last pass over a frame (app/frame_loop.cpp): the old scene's
// last frame fading out over the new one (a scene swap's cross-fade), or
// black over everything for the master brightness.
precision mediump float;

uniform sampler2D u_image;
uniform int u_textured;  // 1: u_image (the old frame); 0: black
uniform float u_alpha;
in vec2 v_uv;
out vec4 o_color;

void main() {
  vec3 c = u_textured == 1 ? texture(u_image, v_uv).rgb : vec3(0.0);
  o_color = vec4(c, u_alpha);
}
