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
// no fixed pace: a sine's steady beat reads as a machine's.
float ember_pulse(float t, float rate, float seed) {
  vec2 x = vec2(t * rate, t * rate * 2.7 + 5.0);
  vec2 i = floor(x), f = fract(x);
  vec2 s = f * f * (3.0 - 2.0 * f);
  float a = mix(hash(vec2(i.x, seed * 97.0)), hash(vec2(i.x + 1.0, seed * 97.0)), s.x);
  float b = mix(hash(vec2(i.y, seed * 97.0 + 13.0)), hash(vec2(i.y + 1.0, seed * 97.0 + 13.0)), s.y);
  return smoothstep(0.15, 0.85, 0.65 * a + 0.35 * b);
}
