#version 300 es
// Puts the Perlin fire, rendered at a fraction of the screen's size into the
// lower-left corner of its own texture, onto the screen, scaled up with
// linear filtering. Drawn with fullscreen.vert, scissored to the fire's box.
precision highp float;

uniform sampler2D u_image;  // premultiplied colour
uniform vec2 u_uv_per_pixel;  // screen pixel -> texture coordinate
out vec4 o_color;

void main() { o_color = textureLod(u_image, gl_FragCoord.xy * u_uv_per_pixel, 0.0); }
