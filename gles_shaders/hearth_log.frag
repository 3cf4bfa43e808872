#version 300 es
// A burning log's static look, rendered once into the hearth's cache (see
// hearth.cpp): bark in long ridges, charred black where the fire licks it
// (the top and the side facing the fire) with cracks in the char, pale end
// grain with rings and a burnt rim. Out: the unlit colour (RGB10_A2) and the
// cracks' glow (two 8-bit halves) with their pulse's two hashes.
// hearth_log_shade.frag lights it and pulses the cracks every frame, so the
// noise here runs only when the view changes.
precision highp float;

in vec3 v_world;
in vec3 v_normal;
in vec3 v_log;
in float v_seed;
in float v_radius;
layout(location = 0) out vec4 o_colour;
layout(location = 1) out vec4 o_crack;

uniform vec3 u_light_pos;
uniform vec3 u_bark;

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
  float facing = max(dot(n, normalize(u_light_pos - v_world)), 0.0);
  vec3 colour;
  o_crack = vec4(0.0);
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
    // 16 bits over two channels: the glow is bright, 8 would band it.
    float hi = floor(crack * 255.0) / 255.0;
    o_crack = vec4(hi, (crack - hi) * 255.0, hash(floor(q * 2.0)), hash(floor(q * 2.0) + 5.0));
  }
  o_colour = vec4(colour, 1.0);
}
