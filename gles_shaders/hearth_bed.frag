#version 300 es
// A bed of embers' static layout, rendered once into the hearth's cache
// (see hearth.cpp): coals (cells of a jittered grid) with dark ash seams,
// each coal glowing from its own hot heart, brighter towards the bed's
// middle. Out: that glow (16 bits over two channels) and the coal's two
// hashes, which set its pulse; hearth_bed_shade.frag pulses and colours it
// every frame, so the cell search runs only when the view changes.
precision highp float;

uniform float u_seed;
in vec2 v_uv;           // -1..1 across the bed
out vec4 o_cache;

vec2 hash2(vec2 p) {
  p = vec2(dot(p, vec2(127.1, 311.7)), dot(p, vec2(269.5, 183.3))) + u_seed;
  return fract(sin(p) * 43758.5453);
}

void main() {
  float r = length(v_uv);
  if (r >= 1.0) discard;
  vec2 p = v_uv * vec2(11.0, 5.0);
  vec2 cell = floor(p), f = fract(p);
  float best = 8.0, second = 8.0;
  vec2 id = vec2(0.0);
  for (int j = -1; j <= 1; ++j)
    for (int i = -1; i <= 1; ++i) {
      vec2 g = vec2(float(i), float(j));
      vec2 o = hash2(cell + g);
      float d = length(g + o - f);
      if (d < best) {
        second = best;
        best = d;
        id = cell + g;
      } else if (d < second) {
        second = d;
      }
    }
  float seam = smoothstep(0.02, 0.14, second - best);  // 0 in the ash between coals
  vec2 h = hash2(id + 17.0);
  float middle = 1.0 - smoothstep(0.15, 1.0, r);
  float heat = seam * (0.35 + 0.65 * h.y) * middle * (1.0 - 0.6 * best);
  float hi = floor(heat * 255.0) / 255.0;
  o_cache = vec4(hi, (heat - hi) * 255.0, h);
}
