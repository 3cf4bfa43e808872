#version 300 es
// One direction of the glow's separable Gaussian blur of the gray image, at
// half size, into this flame's region of the glow atlas. Taps come in pairs
// read with one bilinear fetch each (offsets and weights from the CPU), so a
// radius of r texels costs about r + 1 fetches. The glow is coloured later
// (eigenflame_sprite.frag).
precision highp float;

#define MAX_TAPS 17
uniform sampler2D u_source;
uniform vec4 u_map;       // source uv q = v_uv * u_map.xy + u_map.zw
uniform vec2 u_step;      // one texel of the source, in q
uniform int u_taps;       // centre + pairs
uniform float u_offset[MAX_TAPS];
uniform float u_weight[MAX_TAPS];
uniform vec4 u_src_rect;  // the source region in its atlas, texels (x, y, w, h)
uniform int u_mask;       // 1: zero outside q in [0, 1]^2 (the flame image)
in vec2 v_uv;
out vec4 o_colour;

float fetch(vec2 q) {
  vec2 size = vec2(textureSize(u_source, 0));
  vec2 a = (u_src_rect.xy + clamp(q * u_src_rect.zw, vec2(0.5), u_src_rect.zw - 0.5)) / size;
  float v = texture(u_source, a).r;
  if (u_mask == 1) {
    vec2 inside = step(vec2(0.0), q) * step(q, vec2(1.0));
    v *= inside.x * inside.y;
  }
  return v;
}

void main() {
  vec2 uv = v_uv * u_map.xy + u_map.zw;
  float g = u_weight[0] * fetch(uv);
  for (int i = 1; i < u_taps; ++i) {
    vec2 d = u_step * u_offset[i];
    g += u_weight[i] * (fetch(uv + d) + fetch(uv - d));
  }
  o_colour = vec4(g, 0.0, 0.0, 1.0);
}
