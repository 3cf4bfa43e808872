#version 300 es
// The scene drawn at a reduced size ([display] render_scale or
// render_max_height, scene/scaled_render.h), scaled up to fill the screen
// with linear filtering. Drawn with fullscreen.vert.
precision highp float;

uniform sampler2D u_image;
in vec2 v_uv;
out vec4 o_color;

void main() { o_color = texture(u_image, v_uv); }
