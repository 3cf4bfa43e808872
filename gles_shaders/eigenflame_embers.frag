#version 300 es
// A bed of embers: a glowing ellipse of value noise (value_noise.frag) that
// slowly breathes.
precision highp float;

uniform float u_time;
uniform vec3 u_colour;
in vec2 v_uv;  // -1..1 across the bed
out vec4 o_colour;

void main() {
  float r = length(v_uv);
  float edge = clamp(1.0 - r, 0.0, 1.0);
  vec2 p = v_uv * vec2(9.0, 3.0);
  float n = noise(p + vec2(0.0, u_time * 0.15)) * 0.6 + noise(p * 2.3 - vec2(u_time * 0.1, 0.0)) * 0.4;
  float heat = edge * (0.35 + 0.65 * smoothstep(0.35, 0.9, n)) * (0.85 + 0.15 * sin(u_time * 0.7 + n * 6.0));
  o_colour = vec4(u_colour * heat * heat * 1.6, 1.0);
}
