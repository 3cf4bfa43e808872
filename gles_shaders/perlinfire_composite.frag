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
out vec4 o_color;

void main() {
#ifdef PF_OCCLUDE
  gl_FragDepth = u_depth;  // tested, not written: nearer logs hide the fire
#endif
  vec2 uv = gl_FragCoord.xy * u_uv_per_pixel;
  vec4 t = textureLod(u_image, uv, 0.0);
#if PF_SHADING == 1
  // The halo: a camera's lens and the hot air around a fire spread its
  // brightest light softly around it (the real clips show it around every
  // flame). The exposure blurred by its mipmaps, two levels mixed so the
  // coarse level's texels do not show.
  float g = t.g;
  if (u_halo > 0.0) {
    float blur = 0.5 * (textureLod(u_image, uv, u_halo_lod).r +
                        textureLod(u_image, uv, u_halo_lod + 1.0).r);
    g = max(g, u_halo * blur);
  }
  o_color = fire_ramp(t.r, g, u_color);
#else
  o_color = t;
#endif
}
