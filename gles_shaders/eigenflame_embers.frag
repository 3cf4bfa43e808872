#version 300 es
// A bed of embers: a glowing ellipse of value noise that slowly breathes.
precision highp float;

uniform float u_time;
uniform vec3 u_colour;
uniform float u_seed;
in vec2 v_uv;  // -1..1 across the bed
out vec4 o_colour;

float hash(vec2 p) {
  p = fract(p * vec2(0.1031, 0.1030) + u_seed);
  p += dot(p, p.yx + 33.33);
  return fract((p.x + p.y) * p.x);
}
float noise(vec2 p) {
  vec2 i = floor(p), f = fract(p);
  vec2 u = f * f * (3.0 - 2.0 * f);
  return mix(mix(hash(i), hash(i + vec2(1, 0)), u.x), mix(hash(i + vec2(0, 1)), hash(i + vec2(1, 1)), u.x), u.y);
}

void main() {
  float r = length(v_uv);
  float edge = clamp(1.0 - r, 0.0, 1.0);
  vec2 p = v_uv * vec2(9.0, 3.0);
  float n = noise(p + vec2(0.0, u_time * 0.15)) * 0.6 + noise(p * 2.3 - vec2(u_time * 0.1, 0.0)) * 0.4;
  float heat = edge * (0.35 + 0.65 * smoothstep(0.35, 0.9, n)) * (0.85 + 0.15 * sin(u_time * 0.7 + n * 6.0));
  o_colour = vec4(u_colour * heat * heat * 1.6, 1.0);
}
