#version 300 es
// A bed of embers: coals (cells of a jittered grid) with dark ash seams,
// each coal glowing from its own hot heart and pulsing at its own pace,
// brighter towards the bed's middle; ash and char fade it out at the rim.
// Premultiplied over what is below.
precision highp float;

uniform float u_time;
uniform vec3 u_light;   // the fire's light colour * flicker
uniform float u_seed;
uniform float u_embers; // glow strength
in vec2 v_uv;           // -1..1 across the bed
out vec4 o_color;

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
  float pulse = 0.65 + 0.35 * sin(u_time * (0.6 + 1.4 * h.x) + h.y * 6.2831);
  float middle = 1.0 - smoothstep(0.15, 1.0, r);
  float heat = seam * (0.35 + 0.65 * h.y) * pulse * middle * (1.0 - 0.6 * best);
  heat *= u_embers;
  vec3 glow = vec3(1.0, 0.2, 0.02) * heat * 1.6 + vec3(1.0, 0.55, 0.15) * heat * heat * 1.2;
  vec3 ash = vec3(0.05, 0.04, 0.035) * (0.5 + u_light * 0.5);
  float a = smoothstep(1.0, 0.75, r);
  o_color = vec4((glow + ash * (1.0 - heat)) * a, a);
}
