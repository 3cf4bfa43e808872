#version 300 es
// A bed of embers, every frame: each coal's glow from the hearth's cache
// (hearth_bed.frag, read at this pixel), pulsing at its own irregular pace
// (value_noise.frag's ember_pulse, put before this); ash and
// char fade it out at the rim. Premultiplied over what is below.
precision highp float;

uniform float u_time;
uniform vec3 u_light;   // the fire's light colour * flicker
uniform float u_embers; // glow strength
uniform sampler2D u_cache;
uniform ivec2 u_origin; // the viewport's origin (the cache starts there)
in vec2 v_uv;           // -1..1 across the bed
out vec4 o_color;

void main() {
  float r = length(v_uv);
  if (r >= 1.0) discard;
  vec4 k = texelFetch(u_cache, ivec2(gl_FragCoord.xy) - u_origin, 0);
  float pulse = 0.3 + 0.7 * ember_pulse(u_time, 0.2 + 0.45 * k.z, k.w);
  float heat = (k.x + k.y * (1.0 / 255.0)) * pulse * u_embers;
  vec3 glow = vec3(1.0, 0.2, 0.02) * heat * 1.6 + vec3(1.0, 0.55, 0.15) * heat * heat * 1.2;
  vec3 ash = vec3(0.05, 0.04, 0.035) * (0.5 + u_light * 0.5);
  float a = smoothstep(1.0, 0.75, r);
  o_color = vec4((glow + ash * (1.0 - heat)) * a, a);
}
