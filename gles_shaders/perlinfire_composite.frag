#version 300 es
// Puts the Perlin fire, rendered at a fraction of the screen's size into the
// lower-left corner of its own texture, onto the screen, scaled up with
// linear filtering. Drawn with fullscreen.vert, scissored to the fire's box.
// The builder puts "#define PF_SHADING" (and "#define PF_OCCLUDE" when the
// fire occludes) and fire_ramp.frag in front: flame sheets are stored as
// exposure and coloured here, after upscaling, so their edges stay as crisp
// as the screen's pixels.
precision highp float;

uniform sampler2D u_image;    // PF_SHADING 0: premultiplied colour; 1: exposure
uniform vec2 u_uv_per_pixel;  // screen pixel -> texture coordinate
uniform vec3 u_color;         // the fire's tint (sheets)
uniform float u_halo;         // sheets: the halo's strength (0: none)
uniform float u_halo_lod;     // sheets: the mipmap level whose texels are the halo's blur
uniform float u_depth;        // the fire's middle plane's depth (its `occlude` key: what is nearer hides it)
uniform int u_bspline;        // sheets: 1 scales up by a cubic B-spline (at half the screen's size or less)
uniform vec2 u_texels;        // u_image's size in texels (a uniform: not asked of the texture per pixel)
out vec4 o_color;

#if PF_SHADING == 1
// The exposure scaled up by a cubic B-spline (four bilinear fetches, after
// Sigg and Hadwiger's fast third-order texture filtering): linear filtering
// of a field this coarse (a quarter of the screen's size at the lowest
// quality), then the ramp's steep edge, drew every flame's outline as a
// staircase of the coarse texels. It softens a little too: closer to the
// screen's size (the default 0.7) the outline stays linear, and finer.
vec4 bspline(vec2 uv) {
  vec2 size = u_texels;
  vec2 p = uv * size - 0.5;
  vec2 i = floor(p), f = p - i;
  vec2 f2 = f * f, f3 = f2 * f;
  vec2 w0 = (1.0 - 3.0 * f + 3.0 * f2 - f3) / 6.0;
  vec2 w1 = (4.0 - 6.0 * f2 + 3.0 * f3) / 6.0;
  vec2 w3 = f3 / 6.0;
  vec2 g0 = w0 + w1, g1 = 1.0 - g0;
  vec2 h0 = (i - 0.5 + w1 / g0) / size, h1 = (i + 1.5 + w3 / g1) / size;
  return g0.y * (g0.x * textureLod(u_image, h0, 0.0) + g1.x * textureLod(u_image, vec2(h1.x, h0.y), 0.0)) +
         g1.y * (g0.x * textureLod(u_image, vec2(h0.x, h1.y), 0.0) + g1.x * textureLod(u_image, h1, 0.0));
}
#endif

void main() {
#ifdef PF_OCCLUDE
  gl_FragDepth = u_depth;  // tested, not written: nearer logs hide the fire
#endif
  vec2 uv = gl_FragCoord.xy * u_uv_per_pixel;
#if PF_SHADING == 1
  vec4 t = u_bspline == 1 ? bspline(uv) : textureLod(u_image, uv, 0.0);
  // The halo: a camera's lens and the hot air around a fire spread its
  // brightest light softly around it (the real clips show it around every
  // flame). The exposure blurred by its mipmaps, two levels mixed (one
  // trilinear fetch between them) so the coarse level's texels do not show.
  float g = t.g;
  if (u_halo > 0.0) g = max(g, u_halo * textureLod(u_image, uv, u_halo_lod + 0.5).r);
  o_color = fire_ramp(t.r, g, u_color);
#else
  o_color = textureLod(u_image, uv, 0.0);
#endif
}
