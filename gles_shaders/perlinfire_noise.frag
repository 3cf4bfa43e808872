#version 300 es
// The Perlin fire's noise library (no main): simplex noise in 3-D, 3-D "flow"
// (gradients spun about y in time) and 4-D, plus classic 4-D Perlin noise
// (16 hypercube corners) kept to compare against. Lattice points are hashed
// through a 2-D permutation texture and their gradients read from a gradient
// table texture, both built by firmware/elements/perlinfire/noise_tables.cpp.
// The program builder puts "#version" and the PF_* constants in front of this
// text and the shader body after it; the tests' CPU reference
// (tests/elements/perlinfire/noise_reference.cpp) follows the same steps.
precision highp float;
precision highp int;
precision highp usampler2D;

uniform highp usampler2D u_perm;  // R8UI 256x256: (a, b) -> perm[(perm[a] + b) & 255]
uniform highp sampler2D u_grad3;  // RGBA8_SNORM: (perm2(i, j), k) -> gradient, w = spin +-1
uniform highp sampler2D u_grad4;  // RGBA8_SNORM: (perm2(perm2(i, j), k), l) -> gradient

int pf_perm2(int a, int b) { return int(texelFetch(u_perm, ivec2(a & 255, b & 255), 0).r); }
vec4 pf_grad3(ivec3 c) { return texelFetch(u_grad3, ivec2(pf_perm2(c.x, c.y), c.z & 255), 0); }
vec4 pf_grad4(ivec4 c) {
  return texelFetch(u_grad4, ivec2(pf_perm2(pf_perm2(c.x, c.y), c.z), c.w & 255), 0);
}

float pf_kernel(float d2) {
  float t = max(PF_SIMPLEX_R2 - d2, 0.0);
  t *= t;
  return t * t;
}

// 3-D simplex noise; with `flow`, each corner's gradient turns about y by
// +-angle (cs = cos, sin of it), so the field evolves without moving.
float pf_simplex3(vec3 p, vec2 cs, bool flow) {
  const float kF3 = 1.0 / 3.0;
  const float kG3 = 1.0 / 6.0;
  float s = (p.x + p.y + p.z) * kF3;
  vec3 i = floor(p + s);
  float t = (i.x + i.y + i.z) * kG3;
  vec3 x0 = p - (i - t);
  vec3 g = step(x0.yzx, x0.xyz);
  vec3 l = 1.0 - g;
  vec3 i1 = min(g.xyz, l.zxy);
  vec3 i2 = max(g.xyz, l.zxy);
  vec3 x1 = x0 - i1 + kG3;
  vec3 x2 = x0 - i2 + 2.0 * kG3;
  vec3 x3 = x0 - 1.0 + 3.0 * kG3;
  ivec3 c = ivec3(i - 256.0 * floor(i / 256.0));
  vec4 g0 = pf_grad3(c);
  vec4 g1 = pf_grad3(c + ivec3(i1));
  vec4 g2 = pf_grad3(c + ivec3(i2));
  vec4 g3 = pf_grad3(c + 1);
  if (flow) {
    // x' = x cos + z sin*w, z' = -x sin*w + z cos, w = the corner's spin.
    vec4 sw = cs.y * vec4(g0.w, g1.w, g2.w, g3.w);
    vec4 gx = vec4(g0.x, g1.x, g2.x, g3.x), gz = vec4(g0.z, g1.z, g2.z, g3.z);
    vec4 rx = gx * cs.x + gz * sw;
    vec4 rz = -gx * sw + gz * cs.x;
    g0.xz = vec2(rx.x, rz.x);
    g1.xz = vec2(rx.y, rz.y);
    g2.xz = vec2(rx.z, rz.z);
    g3.xz = vec2(rx.w, rz.w);
  }
  float n = pf_kernel(dot(x0, x0)) * dot(g0.xyz, x0) + pf_kernel(dot(x1, x1)) * dot(g1.xyz, x1) +
            pf_kernel(dot(x2, x2)) * dot(g2.xyz, x2) + pf_kernel(dot(x3, x3)) * dot(g3.xyz, x3);
  return PF_SIMPLEX3_SCALE * n;
}

float pf_snoise3(vec3 p) { return pf_simplex3(p, vec2(1.0, 0.0), false); }
float pf_snoise3_flow(vec3 p, vec2 cs) { return pf_simplex3(p, cs, true); }

// 4-D simplex noise: 5 corners.
float pf_snoise4(vec4 p) {
  const float kF4 = 0.309016994374947451;  // (sqrt(5) - 1) / 4
  const float kG4 = 0.138196601125010504;  // (5 - sqrt(5)) / 20
  float s = (p.x + p.y + p.z + p.w) * kF4;
  vec4 i = floor(p + s);
  float t = (i.x + i.y + i.z + i.w) * kG4;
  vec4 x0 = p - (i - t);
  // Rank each axis by how many of the others it is >= to.
  vec4 rank;
  vec3 is_x = step(x0.yzw, x0.xxx);
  vec3 is_yz = step(x0.zww, x0.yyz);
  rank.x = is_x.x + is_x.y + is_x.z;
  rank.yzw = 1.0 - is_x;
  rank.y += is_yz.x + is_yz.y;
  rank.zw += 1.0 - is_yz.xy;
  rank.z += is_yz.z;
  rank.w += 1.0 - is_yz.z;
  vec4 i3 = clamp(rank, 0.0, 1.0);
  vec4 i2 = clamp(rank - 1.0, 0.0, 1.0);
  vec4 i1 = clamp(rank - 2.0, 0.0, 1.0);
  vec4 x1 = x0 - i1 + kG4;
  vec4 x2 = x0 - i2 + 2.0 * kG4;
  vec4 x3 = x0 - i3 + 3.0 * kG4;
  vec4 x4 = x0 - 1.0 + 4.0 * kG4;
  ivec4 c = ivec4(i - 256.0 * floor(i / 256.0));
  float n = pf_kernel(dot(x0, x0)) * dot(pf_grad4(c), x0) +
            pf_kernel(dot(x1, x1)) * dot(pf_grad4(c + ivec4(i1)), x1) +
            pf_kernel(dot(x2, x2)) * dot(pf_grad4(c + ivec4(i2)), x2) +
            pf_kernel(dot(x3, x3)) * dot(pf_grad4(c + ivec4(i3)), x3) +
            pf_kernel(dot(x4, x4)) * dot(pf_grad4(c + 1), x4);
  return PF_SIMPLEX4_SCALE * n;
}

// Classic 4-D Perlin noise: gradients at all 16 corners of the hypercube,
// blended with the quintic fade; the baseline simplex noise is measured against.
float pf_pnoise4(vec4 p) {
  vec4 i = floor(p);
  vec4 f = p - i;
  vec4 u = f * f * f * (f * (f * 6.0 - 15.0) + 10.0);
  ivec4 c = ivec4(i - 256.0 * floor(i / 256.0));
  float n[16];
  for (int b = 0; b < 16; ++b) {
    ivec4 o = ivec4(b & 1, (b >> 1) & 1, (b >> 2) & 1, (b >> 3) & 1);
    n[b] = dot(pf_grad4(c + o), f - vec4(o));
  }
  for (int b = 0; b < 8; ++b) n[b] = mix(n[2 * b], n[2 * b + 1], u.x);
  for (int b = 0; b < 4; ++b) n[b] = mix(n[2 * b], n[2 * b + 1], u.y);
  for (int b = 0; b < 2; ++b) n[b] = mix(n[2 * b], n[2 * b + 1], u.z);
  return PF_PERLIN4_SCALE * mix(n[0], n[1], u.w);
}
