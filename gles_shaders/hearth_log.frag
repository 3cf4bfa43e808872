#version 300 es
// A burning log: bark in long ridges, charred black where the fire licks
// it (the top and the side facing the fire) with cracks glowing and pulsing
// in the char, pale end grain with rings and a burnt rim; lit by the fire's
// flickering light (u_light: colour * flicker, w: ember strength).
precision highp float;

in vec3 v_world;
in vec3 v_normal;
in vec3 v_log;
in float v_seed;
in float v_radius;
out vec4 o_color;

uniform vec3 u_camera;
uniform vec3 u_light_pos;
uniform vec4 u_light;
uniform vec3 u_bark;
uniform float u_time;

float hash(vec2 p) {
  p = fract(p * vec2(0.1031, 0.1030));
  p += dot(p, p.yx + 33.33);
  return fract((p.x + p.y) * p.x);
}
float noise(vec2 p) {
  vec2 i = floor(p), f = fract(p);
  vec2 s = f * f * (3.0 - 2.0 * f);
  return mix(mix(hash(i), hash(i + vec2(1, 0)), s.x), mix(hash(i + vec2(0, 1)), hash(i + vec2(1, 1)), s.x), s.y);
}
float fbm(vec2 p) { return 0.55 * noise(p) + 0.3 * noise(p * 2.1 + 7.0) + 0.15 * noise(p * 4.3 + 3.0); }

void main() {
  vec3 n = normalize(v_normal);
  vec3 to_light = u_light_pos - v_world;
  float d2 = dot(to_light, to_light);
  float facing = max(dot(n, normalize(to_light)), 0.0);
  vec3 lit = u_light.rgb * (0.45 + 2.2 * facing) / (1.0 + d2 * 2.0);
  vec3 colour;
  float glow = 0.0;
  if (v_log.z > 0.5) {
    // End grain: rings, pale wood, burnt towards the rim.
    float r = v_radius;
    float rings = 0.5 + 0.5 * sin(r * 40.0 + noise(vec2(r * 9.0, v_seed)) * 3.0);
    colour = mix(vec3(0.42, 0.3, 0.19), vec3(0.3, 0.2, 0.12), rings) * (1.0 - 0.85 * smoothstep(0.6, 0.95, r));
  } else {
    vec2 q = vec2(v_log.y * 14.0 + v_seed, v_log.x * 5.0);
    float ridges = fbm(vec2(q.x * 1.6, q.y * 0.35));  // long furrows along the log
    colour = u_bark * (0.45 + 0.8 * ridges);
    // Char: where the fire reaches (up, and towards the light), with crackle.
    float heat = clamp(facing * 0.7 + n.y * 0.5, 0.0, 1.0);
    float crack_field = fbm(q * 1.3 + vec2(0.0, v_seed));
    float char_amount = smoothstep(0.6, 0.95, heat + 0.35 * (crack_field - 0.5));
    colour = mix(colour, vec3(0.07, 0.055, 0.045), char_amount);
    // Cracks in the char: thin bands of a cellular-ish field, glowing.
    float c = abs(fbm(q * 2.2 + 11.0) - 0.5);
    float patches = smoothstep(0.45, 0.75, fbm(q * 0.6 + 23.0));  // glowing only in places
    float crack = smoothstep(0.035, 0.0, c) * char_amount * patches;
    float pulse = 0.6 + 0.4 * sin(u_time * (1.3 + hash(floor(q * 2.0)) * 2.0) + hash(floor(q * 2.0) + 5.0) * 6.28);
    glow = crack * pulse * u_light.w;
  }
  vec3 ember = vec3(1.0, 0.32, 0.05) * glow * 1.6 + vec3(1.0, 0.7, 0.3) * pow(glow, 3.0) * 0.6;
  o_color = vec4(colour * (lit + vec3(0.03)) + ember, 1.0);
}
