#version 300 es
// A burning log, every frame: its static look from the hearth's cache
// (hearth_log.frag, read at this pixel), lit by the fire's flickering light
// (u_light: colour * flicker, w: ember strength), its cracks glowing and
// pulsing each at its own pace.
precision highp float;

in vec3 v_world;
in vec3 v_normal;
out vec4 o_color;

uniform vec3 u_light_pos;
uniform vec4 u_light;
uniform float u_time;
uniform sampler2D u_colour;  // the cache: unlit colour
uniform sampler2D u_crack;   // crack glow (hi, lo), pulse hashes
uniform ivec2 u_origin;      // the viewport's origin (the cache starts there)

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy) - u_origin;
  vec3 colour = texelFetch(u_colour, p, 0).rgb;
  vec4 k = texelFetch(u_crack, p, 0);
  vec3 n = normalize(v_normal);
  vec3 to_light = u_light_pos - v_world;
  float d2 = dot(to_light, to_light);
  float facing = max(dot(n, normalize(to_light)), 0.0);
  vec3 lit = u_light.rgb * (0.45 + 2.2 * facing) / (1.0 + d2 * 2.0);
  // The coals under the logs light their undersides and lower flanks.
  lit += u_light.rgb * vec3(1.0, 0.6, 0.35) * (0.55 * u_light.w * max(-n.y + 0.3, 0.0));
  float crack = k.x + k.y * (1.0 / 255.0);
  float pulse = 0.6 + 0.4 * sin(u_time * (1.3 + k.z * 2.0) + k.w * 6.28);
  float glow = crack * pulse * u_light.w;
  vec3 ember = vec3(1.0, 0.32, 0.05) * glow * 1.6 + vec3(1.0, 0.7, 0.3) * pow(glow, 3.0) * 0.6;
  o_color = vec4(colour * (lit + vec3(0.03)) + ember, 1.0);
}
