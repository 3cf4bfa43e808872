#version 300 es
// A bed of embers' static layout, rendered once into the hearth's cache
// (see hearth.cpp): broken coals of many sizes (cells of a jittered grid,
// the grid itself warped so no two are alike) between dark gaps of uneven
// width; some coals burnt out black, the rest glowing in blotches and specks,
// most at their own hot heart, under patches of ash; brighter towards the
// bed's middle. A coal's even glow between thin
// seams of one width read as a tiled floor. Out: that glow (16 bits over two
// channels) and the coal's two hashes, which set its pulse;
// hearth_bed_shade.frag pulses and colours it every frame, so the cell
// search runs only when the view changes. value_noise.frag goes in front.
precision highp float;

uniform float u_seed;
in vec2 v_uv;           // -1..1 across the bed
out vec4 o_cache;

vec2 hash2(vec2 p) {
  p = vec2(dot(p, vec2(127.1, 311.7)), dot(p, vec2(269.5, 183.3))) + u_seed;
  return fract(sin(p) * 43758.5453);
}

// The nearest and second nearest cell centre's distances and the nearest cell.
vec4 cells(vec2 p) {
  vec2 cell = floor(p), f = fract(p);
  float best = 8.0, second = 8.0;
  vec2 id = vec2(0.0);
  for (int j = -1; j <= 1; ++j)
    for (int i = -1; i <= 1; ++i) {
      vec2 g = vec2(float(i), float(j));
      float d = length(g + hash2(cell + g) - f);
      if (d < best) {
        second = best;
        best = d;
        id = cell + g;
      } else if (d < second) {
        second = d;
      }
    }
  return vec4(best, second, id);
}

void main() {
  float r = length(v_uv);
  if (r >= 1.0) discard;
  vec2 p = v_uv * vec2(11.0, 5.0);
  // Warp the grid: coals of unlike sizes and shapes, none a tile.
  p += 0.9 * (vec2(fbm(p * 0.45 + 3.0), fbm(p * 0.45 + 11.0)) - 0.5);
  vec4 coal = cells(p);
  vec2 h = hash2(coal.zw + 17.0);
  // The gaps between coals: dark, from a hairline to half a coal wide; each
  // coal rounded, its glow falling off towards its edge.
  float gap = mix(0.0, 0.14, noise(p * 0.7 + 5.0));
  float solid = smoothstep(gap, gap + 0.25, coal.y - coal.x);
  // About one coal in five has burnt out: black charcoal with a faint glow.
  float alive = mix(0.1, 1.0, smoothstep(0.16, 0.26, h.x));
  // Its face glows in blotches and specks, not as a lit plate.
  float g = noise(p * 4.3 + h * 37.0);
  float grain = 0.25 + 1.1 * g * g + 0.35 * noise(p * 10.5 + 7.0);
  float face = (0.45 + 0.55 * h.y) * (1.0 - 0.4 * coal.x) * grain;
  // Grey ash lies over some of the bed in soft patches and dulls the glow.
  float ash = smoothstep(0.5, 0.75, fbm(p * 0.9 + 23.0));
  float middle = 1.0 - smoothstep(0.15, 1.0, r);
  float heat = 1.4 * solid * alive * middle * face * (1.0 - 0.6 * ash);
  heat = clamp(heat, 0.0, 1.0);
  float hi = floor(heat * 255.0) / 255.0;
  o_cache = vec4(hi, (heat - hi) * 255.0, h);
}
