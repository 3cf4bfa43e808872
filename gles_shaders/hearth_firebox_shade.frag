#version 300 es
// The firebox, every frame: its lit colour from the hearth's cache
// (hearth_firebox.frag, read at this pixel) under the fire's flicker, the
// left and right halves of the fire flickering apart, so the light moves
// over the bricks as the flames do.
precision highp float;

out vec4 o_color;

uniform vec2 u_flicker;     // the left and right halves' light, about 1 on average
uniform sampler2D u_cache;  // rgb: sqrt of the lit colour at half scale; a: the left half's share
uniform ivec2 u_origin;      // the viewport's origin (the cache starts there)

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy) - u_origin;
  vec4 c = texelFetch(u_cache, p, 0);
  o_color = vec4(c.rgb * c.rgb * (2.0 * mix(u_flicker.y, u_flicker.x, c.a)), 1.0);
}
