#version 300 es
// Value noise (no main): a hash of a lattice point, smooth value noise and
// three octaves of it, for the hearth's logs and firebox and the eigen-flames'
// ember bed, and an ember's irregular pulse in time. Put before the shader that uses it:
// Program::from_library(vert, {"value_noise.frag", "x.frag"}).
// u_noise_seed shifts the hash (a program that does not set it gets 0).
precision highp float;

uniform float u_noise_seed;

float hash(vec2 p) {
  p = fract(p * vec2(0.1031, 0.1030) + u_noise_seed);
  p += dot(p, p.yx + 33.33);
  return fract((p.x + p.y) * p.x);
}
float noise(vec2 p) {
  vec2 i = floor(p), f = fract(p);
  vec2 s = f * f * (3.0 - 2.0 * f);
  return mix(mix(hash(i), hash(i + vec2(1, 0)), s.x), mix(hash(i + vec2(0, 1)), hash(i + vec2(1, 1)), s.x), s.y);
}
float fbm(vec2 p) { return 0.55 * noise(p) + 0.3 * noise(p * 2.1 + 7.0) + 0.15 * noise(p * 4.3 + 3.0); }
// An ember's glow in time, 0..1: two octaves of smooth 1-D noise through a
// random value every 1/rate s (seed: the ember's own, 0..1), stretched so it
// spends time both dim and flaring. Air reaching a coal comes and goes at
// no fixed pace: a sine's steady beat reads as a machine's. Its random
// values come from an integer hash: hash()'s float arithmetic rounds
// differently on x86 and arm64 (fused multiply-add, most likely), and the glowing cracks
// then differed by up to 65 of 255 between the two builds' frames.
// (highp: a fragment shader's ints are mediump by default, 16 bits on some GPUs.)
float ember_value(float i, highp uint seed) {
  highp uint h = uint(int(i)) * 747796405u + seed * 2891336453u;
  h = (h ^ (h >> 16u)) * 2246822519u;
  h = (h ^ (h >> 13u)) * 3266489917u;
  return float(h >> 8u) * (1.0 / 16777216.0);
}
float ember_pulse(float t, float rate, float seed) {
  highp uint s = uint(seed * 255.0 + 0.5);
  vec2 x = vec2(t * rate, t * rate * 2.7 + 5.0);
  vec2 i = floor(x), f = fract(x);
  vec2 w = f * f * (3.0 - 2.0 * f);
  float a = mix(ember_value(i.x, s), ember_value(i.x + 1.0, s), w.x);
  float b = mix(ember_value(i.y, s + 256u), ember_value(i.y + 1.0, s + 256u), w.y);
  return smoothstep(0.15, 0.85, 0.65 * a + 0.35 * b);
}
